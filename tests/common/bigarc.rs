//! The constant-gradient arc evaluated in 320-bit arithmetic (astro-float), through the
//! hyperbolic form τ = τ0 + |F|s, tanh τ0 = cos β, sech τ0 = sin β:
//! x(s) − x0 = [ln(cosh τ / cosh τ0) F̂ + (gd τ − gd τ0) p̂]/|F|, t̂(s) = tanh τ F̂ + sech τ p̂,
//! gd y = 2 atan(eʸ) − π/2. This is a different route from the f64 recipe under test (no
//! tan(β/2), no expm1/ln1p splitting, no series), so agreement checks the recipe's algebra and
//! its rounding at once. The inputs are the exact f64 vectors the f64 code receives.

use astro_float::{BigFloat, Consts, RoundingMode};
use glam::DVec3;

const P: usize = 320;
const RM: RoundingMode = RoundingMode::ToEven;

struct V([BigFloat; 3]);

fn bf(x: f64) -> BigFloat {
    BigFloat::from_f64(x, P)
}

fn to_f64(x: &BigFloat) -> f64 {
    let s = format!("{x}");
    s.parse::<f64>()
        .unwrap_or_else(|_| panic!("cannot parse {s}"))
}

impl V {
    fn from(v: DVec3) -> Self {
        V([bf(v.x), bf(v.y), bf(v.z)])
    }
    fn dot(&self, o: &V) -> BigFloat {
        let mut acc = bf(0.0);
        for i in 0..3 {
            acc = acc.add(&self.0[i].mul(&o.0[i], P, RM), P, RM);
        }
        acc
    }
    fn cross(&self, o: &V) -> V {
        let (a, b) = (&self.0, &o.0);
        let d = |i: usize, j: usize| a[i].mul(&b[j], P, RM).sub(&a[j].mul(&b[i], P, RM), P, RM);
        V([d(1, 2), d(2, 0), d(0, 1)])
    }
    fn norm(&self) -> BigFloat {
        self.dot(self).sqrt(P, RM)
    }
    fn scale(&self, k: &BigFloat) -> V {
        V([
            self.0[0].mul(k, P, RM),
            self.0[1].mul(k, P, RM),
            self.0[2].mul(k, P, RM),
        ])
    }
}

/// (position − origin, unit direction) after arclength `s` from direction `t0` under constant
/// F = `force` (≠ 0, not parallel to t0), each rounded to f64.
pub fn exact_arc(t0: DVec3, force: DVec3, s: f64) -> (DVec3, DVec3) {
    let mut cc = Consts::new().expect("constants");
    let t = V::from(t0);
    let f = V::from(force);
    let tn = t.norm();
    let fnorm = f.norm();
    let k = t.cross(&f);
    let norm = tn.mul(&fnorm, P, RM);
    let sigma = k.norm().div(&norm, P, RM);
    let c = t.dot(&f).div(&norm, P, RM);
    let one = bf(1.0);
    // e^τ0 = (1 + c)/σ = σ/(1 − c): the cancellation-free one of the two.
    let e_tau0 = if c.is_negative() {
        sigma.div(&one.sub(&c, P, RM), P, RM)
    } else {
        one.add(&c, P, RM).div(&sigma, P, RM)
    };
    let tau0 = e_tau0.ln(P, RM, &mut cc);
    let x = fnorm.mul(&bf(s), P, RM);
    let tau = tau0.add(&x, P, RM);
    let e_tau = e_tau0.mul(&x.exp(P, RM, &mut cc), P, RM);
    let cosh_ratio = tau
        .cosh(P, RM, &mut cc)
        .div(&tau0.cosh(P, RM, &mut cc), P, RM);
    let along = cosh_ratio.ln(P, RM, &mut cc).div(&fnorm, P, RM);
    let across = e_tau
        .atan(P, RM, &mut cc)
        .sub(&e_tau0.atan(P, RM, &mut cc), P, RM)
        .mul(&bf(2.0), P, RM)
        .div(&fnorm, P, RM);
    let tanh = tau.tanh(P, RM, &mut cc);
    let sech = one.div(&tau.cosh(P, RM, &mut cc), P, RM);
    let f_hat = f.scale(&one.div(&fnorm, P, RM));
    let fk = f.cross(&k);
    let p_hat = fk.scale(&one.div(&fk.norm(), P, RM));
    let comb = |u: &BigFloat, v: &BigFloat| {
        let w = f_hat.scale(u);
        let z = p_hat.scale(v);
        DVec3::new(
            to_f64(&w.0[0].add(&z.0[0], P, RM)),
            to_f64(&w.0[1].add(&z.0[1], P, RM)),
            to_f64(&w.0[2].add(&z.0[2], P, RM)),
        )
    };
    (comb(&along, &across), comb(&tanh, &sech))
}
