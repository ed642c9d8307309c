//! A pbrt-v4 dielectric's index of refraction: a number, or a spectrum over wavelength — pbrt's
//! piecewise-linear n(λ) through nodes, given inline or by one of its named glasses
//! (`"spectrum eta" "glass-BK7"` and the rest, as pbrt-v4 tabulates them in
//! `src/pbrt/util/spectrum.cpp` from refractiveindex.info, CC0; pbrt names three by another
//! glass's data: `glass-F5`, `glass-F10` and `glass-F11` are its tables of Schott's SF5, SF10
//! and SF11). Outside a spectrum's nodes pbrt reads 0, and its dielectric then takes the index
//! 1 (`materials.h`: no surface at all at that wavelength).

use toml::Value as Toml;

/// A dielectric's index as pbrt-v4 gives it (see the module's notes).
#[derive(Clone, Debug, PartialEq)]
pub enum Eta {
    /// The same at every wavelength.
    Constant(f64),
    /// pbrt's piecewise-linear spectrum through nodes (nm, n), ascending in nm.
    Spectrum(Vec<(f64, f64)>),
}

/// How far beyond a spectrum's first or last node grinlight's table steps to pbrt's index 1, nm.
const EDGE: f64 = 1e-3;

/// How far either side of each of pbrt's nodes grinlight's table has rows too, nm: a monotone
/// cubic through rows on two lines bends only between the rows about their corner.
const KINK: f64 = 1e-2;

impl Eta {
    /// n at vacuum wavelength `nm` as pbrt-v4's dielectric takes it.
    pub fn at(&self, nm: f64) -> f64 {
        let nodes = match self {
            Eta::Constant(n) => return *n,
            Eta::Spectrum(nodes) => nodes,
        };
        let (first, last) = (nodes[0], nodes[nodes.len() - 1]);
        if nm < first.0 || nm > last.0 {
            return 1.0;
        }
        let i = nodes
            .partition_point(|&(x, _)| x <= nm)
            .clamp(1, nodes.len() - 1);
        let ((x0, n0), (x1, n1)) = (nodes[i - 1], nodes[i]);
        match x1 > x0 {
            true => n0 + (n1 - n0) * (nm - x0) / (x1 - x0),
            false => n0,
        }
    }

    /// grinlight's form of it: the number, or `{ table = [[nm, n], …] }` with n at every whole
    /// nanometre from 360 to 830, at every node between and [`KINK`] either side of it —
    /// grinlight's monotone cubic through those rows keeps to pbrt's line within 10⁻⁷ (tested)
    /// — and 1 from [`EDGE`] beyond the first and last nodes, where pbrt's dielectric is no
    /// surface.
    pub fn toml(&self) -> Toml {
        let nodes = match self {
            Eta::Constant(n) => return Toml::Float(*n),
            Eta::Spectrum(nodes) => nodes,
        };
        let (first, last) = (nodes[0].0, nodes[nodes.len() - 1].0);
        let (lo, hi) = (crate::spectrum::LAMBDA_MIN, crate::spectrum::LAMBDA_MAX);
        let mut at: Vec<f64> = (lo as usize..=hi as usize).map(|nm| nm as f64).collect();
        at.extend(
            nodes
                .iter()
                .flat_map(|&(nm, _)| [nm - KINK, nm, nm + KINK])
                .filter(|nm| (lo..=hi).contains(nm)),
        );
        at.extend(
            [first - EDGE, last + EDGE]
                .into_iter()
                .filter(|nm| (lo..=hi).contains(nm)),
        );
        at.sort_by(f64::total_cmp);
        at.dedup();
        let rows = at
            .into_iter()
            .map(|nm| Toml::Array(vec![Toml::Float(nm), Toml::Float(self.at(nm))]))
            .collect();
        Toml::Table(toml::map::Map::from_iter([(
            "table".to_string(),
            Toml::Array(rows),
        )]))
    }

    /// The bits that tell two indices apart (for reusing what was made of one).
    pub fn key(&self) -> Vec<u64> {
        match self {
            Eta::Constant(n) => vec![n.to_bits()],
            Eta::Spectrum(nodes) => nodes
                .iter()
                .flat_map(|&(nm, n)| [nm.to_bits(), n.to_bits()])
                .collect(),
        }
    }
}

/// The nodes (nm, n) of pbrt-v4's glass `name` (None: not one of its glasses).
pub fn glass(name: &str) -> Option<&'static [(f64, f64)]> {
    Some(match name {
        "glass-BK7" => &BK7,
        "glass-BAF10" => &BAF10,
        "glass-FK51A" => &FK51A,
        "glass-LASF9" => &LASF9,
        "glass-F5" => &SF5,
        "glass-F10" => &SF10,
        "glass-F11" => &SF11,
        _ => return None,
    })
}

/// The names pbrt-v4 gives its glasses.
pub const NAMES: [&str; 7] = [
    "glass-BK7",
    "glass-BAF10",
    "glass-FK51A",
    "glass-LASF9",
    "glass-F5",
    "glass-F10",
    "glass-F11",
];

const BK7: [(f64, f64); 29] = [
    (300.0, 1.5527702635739),
    (322.0, 1.5458699289209),
    (344.0, 1.5404466868331),
    (366.0, 1.536090527917),
    (388.0, 1.53252773217),
    (410.0, 1.529568767224),
    (432.0, 1.5270784291406),
    (454.0, 1.5249578457324),
    (476.0, 1.5231331738499),
    (498.0, 1.5215482528369),
    (520.0, 1.5201596882463),
    (542.0, 1.5189334783109),
    (564.0, 1.5178426478869),
    (586.0, 1.516865556749),
    (608.0, 1.5159846691816),
    (630.0, 1.5151856452759),
    (652.0, 1.5144566604975),
    (674.0, 1.513787889767),
    (696.0, 1.5131711117948),
    (718.0, 1.5125994024544),
    (740.0, 1.5120668948646),
    (762.0, 1.5115685899969),
    (784.0, 1.5111002059336),
    (806.0, 1.5106580569705),
    (828.0, 1.5102389559626),
    (850.0, 1.5098401349174),
    (872.0, 1.5094591800239),
    (894.0, 1.5090939781792),
    (916.0, 1.5087426727363),
];

const BAF10: [(f64, f64); 27] = [
    (350.0, 1.7126880848268),
    (371.0, 1.7044510025682),
    (393.0, 1.6978539633931),
    (414.0, 1.6924597573902),
    (436.0, 1.6879747521657),
    (457.0, 1.6841935148947),
    (479.0, 1.6809676313681),
    (500.0, 1.6781870617363),
    (522.0, 1.6757684467878),
    (543.0, 1.6736474831891),
    (565.0, 1.6717737892968),
    (586.0, 1.6701073530462),
    (608.0, 1.6686160168249),
    (629.0, 1.6672736605352),
    (651.0, 1.6660588657981),
    (672.0, 1.6649539185393),
    (694.0, 1.6639440538738),
    (715.0, 1.6630168772865),
    (737.0, 1.6621619159417),
    (758.0, 1.6613702672977),
    (780.0, 1.6606343213443),
    (801.0, 1.6599475391478),
    (823.0, 1.6593042748862),
    (844.0, 1.6586996317841),
    (866.0, 1.6581293446924),
    (887.0, 1.6575896837763),
    (909.0, 1.6570773750475),
];

const FK51A: [(f64, f64); 29] = [
    (290.0, 1.5145777204082),
    (312.0, 1.5092112868865),
    (334.0, 1.5049961987453),
    (356.0, 1.5016153970446),
    (378.0, 1.4988558885761),
    (400.0, 1.496569610433),
    (422.0, 1.4946506898002),
    (444.0, 1.4930216011953),
    (466.0, 1.4916244098644),
    (488.0, 1.49041505042),
    (511.0, 1.4893594837084),
    (533.0, 1.4884310526027),
    (555.0, 1.4876086240083),
    (577.0, 1.486875258765),
    (599.0, 1.486217243501),
    (621.0, 1.4856233753353),
    (643.0, 1.4850844262039),
    (665.0, 1.4845927367446),
    (687.0, 1.484141904927),
    (709.0, 1.483726544853),
    (732.0, 1.4833420981287),
    (754.0, 1.4829846850495),
    (776.0, 1.482650986233),
    (798.0, 1.4823381477539),
    (820.0, 1.4820437045732),
    (842.0, 1.4817655183243),
    (864.0, 1.481501726448),
    (886.0, 1.4812507003621),
    (908.0, 1.4810110108734),
];

const LASF9: [(f64, f64); 26] = [
    (370.0, 1.9199725545705),
    (391.0, 1.9057858245373),
    (412.0, 1.8945401582481),
    (433.0, 1.8854121949451),
    (455.0, 1.877863643024),
    (476.0, 1.8715257028176),
    (497.0, 1.8661362648008),
    (519.0, 1.8615034773283),
    (540.0, 1.8574834752011),
    (561.0, 1.8539661699122),
    (583.0, 1.8508658556),
    (604.0, 1.8481148099285),
    (625.0, 1.8456588222442),
    (646.0, 1.8434539988324),
    (668.0, 1.8414644361915),
    (689.0, 1.8396604975285),
    (710.0, 1.8380175167434),
    (732.0, 1.8365148106821),
    (753.0, 1.8351349171703),
    (774.0, 1.8338630007484),
    (796.0, 1.8326863845545),
    (817.0, 1.8315941782006),
    (838.0, 1.8305769794709),
    (859.0, 1.8296266333424),
    (881.0, 1.8287360359155),
    (902.0, 1.8278989738228),
];

const SF5: [(f64, f64); 26] = [
    (370.0, 1.7286549847245),
    (391.0, 1.7170151864402),
    (412.0, 1.7079037179421),
    (433.0, 1.7005724270177),
    (455.0, 1.6945472844297),
    (476.0, 1.6895110487297),
    (497.0, 1.685242265691),
    (519.0, 1.6815810964),
    (540.0, 1.678409006027),
    (561.0, 1.6756360973958),
    (583.0, 1.6731928929908),
    (604.0, 1.6710248234743),
    (625.0, 1.6690884260039),
    (646.0, 1.6673486579281),
    (668.0, 1.6657769585173),
    (689.0, 1.6643498246044),
    (710.0, 1.6630477468358),
    (732.0, 1.6618544037398),
    (753.0, 1.6607560432197),
    (774.0, 1.6597410023473),
    (796.0, 1.6587993305922),
    (817.0, 1.6579224913632),
    (838.0, 1.6571031234995),
    (859.0, 1.6563348491305),
    (881.0, 1.6556121177295),
    (902.0, 1.654930078671),
];

const SF10: [(f64, f64); 26] = [
    (380.0, 1.7905788948419),
    (401.0, 1.7776074571692),
    (422.0, 1.7673620572474),
    (443.0, 1.7590649148507),
    (464.0, 1.7522127524444),
    (486.0, 1.7464635698826),
    (507.0, 1.741575877046),
    (528.0, 1.7373738218659),
    (549.0, 1.7337260730259),
    (570.0, 1.7305324562829),
    (592.0, 1.7277151818026),
    (613.0, 1.7252129043714),
    (634.0, 1.7229765939984),
    (655.0, 1.7209665988467),
    (676.0, 1.719150514229),
    (698.0, 1.7175016091415),
    (719.0, 1.7159976462946),
    (740.0, 1.7146199848831),
    (761.0, 1.7133528897994),
    (782.0, 1.7121829937648),
    (804.0, 1.7110988742233),
    (825.0, 1.7100907173852),
    (846.0, 1.7091500491754),
    (867.0, 1.7082695180523),
    (888.0, 1.7074427184169),
    (910.0, 1.7066640460471),
];

const SF11: [(f64, f64); 26] = [
    (370.0, 1.8700216173234),
    (391.0, 1.8516255860581),
    (412.0, 1.8374707714715),
    (433.0, 1.8262323798466),
    (455.0, 1.8170946940119),
    (476.0, 1.8095242343848),
    (497.0, 1.803155581666),
    (519.0, 1.7977291183308),
    (540.0, 1.7930548640505),
    (561.0, 1.7889903663666),
    (583.0, 1.7854266026774),
    (604.0, 1.7822786683156),
    (625.0, 1.7794794394722),
    (646.0, 1.7769751487395),
    (668.0, 1.7747222267051),
    (689.0, 1.7726850031375),
    (710.0, 1.770834004936),
    (732.0, 1.7691446766161),
    (753.0, 1.7675964052635),
    (774.0, 1.7661717683505),
    (796.0, 1.764855947008),
    (817.0, 1.7636362637211),
    (838.0, 1.7625018146862),
    (859.0, 1.7614431749629),
    (881.0, 1.7604521601554),
    (902.0, 1.7595216323879),
];

#[cfg(test)]
mod tests {
    use super::*;
    use crate::media::MonotoneCubic;

    /// grinlight's reading of each glass's converted table — a monotone cubic through its rows
    /// (`MonotoneCubic`, as the scene reader makes it) — keeps to pbrt's piecewise-linear n(λ)
    /// within 10⁻⁷ at every 0.01 nm from 360 to 830, but within [`EDGE`] of the first node,
    /// where pbrt steps from 1 to the glass's index and the table ramps.
    #[test]
    fn each_glass_converts_to_pbrts_index_within_1e_7() {
        for name in NAMES {
            let eta = Eta::Spectrum(glass(name).unwrap().to_vec());
            let Toml::Table(t) = eta.toml() else {
                panic!("{name}: not a table")
            };
            let rows: Vec<(f64, f64)> = t["table"]
                .as_array()
                .unwrap()
                .iter()
                .map(|r| {
                    let r = r.as_array().unwrap();
                    (r[0].as_float().unwrap(), r[1].as_float().unwrap())
                })
                .collect();
            let (x, y) = rows.into_iter().unzip();
            let cubic = MonotoneCubic::new(x, y, false, ("nm", "n")).unwrap();
            let first = glass(name).unwrap()[0].0;
            let worst = (0..47_000)
                .map(|k| 360.0 + 0.01 * k as f64)
                .filter(|nm| !(first - EDGE..first).contains(nm))
                .map(|nm| (cubic.at(nm).0 - eta.at(nm)).abs())
                .fold(0.0, f64::max);
            assert!(worst < 1e-7, "{name}: {worst}");
        }
    }
}
