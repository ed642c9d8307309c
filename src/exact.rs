//! Exact, order-independent sums of reals: what makes results rendered apart (other passes,
//! other photons, other machines) merge into bit for bit the result of one run. A float sum
//! rounds at every addition, so (a + b) + c and a + (b + c) may differ in the last bit; these
//! sums keep an integer instead, and integer addition is associative.
//!
//! - [`ExactSum`]: the exact sum of any f64 values (a "superaccumulator": f64's binary range
//!   as 32-bit digits, kept over the window its values reach), read back correctly rounded:
//!   for receivers' bins and energy budgets.
//! - [`Fixed`]: a fixed-point number with 64 integer and 64 fraction bits, 16 bytes: for films,
//!   whose millions of pixels could not each hold an `ExactSum`. Values must lie in
//!   (−2⁶², 2⁶²) and are kept to 2⁻⁶⁴ ≈ 5.4·10⁻²⁰; see [`Fixed::from_f64`].

use serde::{Deserialize, Serialize};

/// Additions between carry propagations: each changes a digit by less than 2³², an i64 holds
/// 2⁶³, so 2³⁰ leaves a factor 2 spare.
const ADDS_BEFORE_CARRY: u32 = 1 << 30;

/// Digit positions an exact sum can reach: f64's 2098 binary positions (2⁻¹⁰⁷⁴ to 2¹⁰²⁴) are
/// 66 digits; carries of up to 2⁶⁴ additions reach two more; 72 leaves room.
const MAX_POSITIONS: usize = 72;

/// The exact sum of f64 values: Σ dᵢ·2^(32(lo + i) − 1074) over 32-bit digits dᵢ, kept only
/// over the window of digits its values reach (a bin's photon fluxes span a few digits, so a
/// sum is tens of bytes, not the 544 the whole f64 range would take). Adding is exact (no
/// rounding, whatever the order or grouping); [`ExactSum::value`] rounds once. A non-finite
/// value added makes the sum non-finite (NaN, or the infinity added), never silently finite.
#[derive(Clone, Debug, Default, Serialize, Deserialize)]
pub struct ExactSum {
    /// The digit position of `digits[0]`.
    lo: u32,
    /// Digits, least significant first; between carries each may exceed 32 bits. The last is
    /// signed (two's complement over the window).
    digits: Vec<i64>,
    /// Additions since the last carry propagation.
    #[serde(skip)]
    adds: u32,
    /// The sum of the non-finite values added (0 when none).
    special: f64,
}

impl PartialEq for ExactSum {
    fn eq(&self, other: &Self) -> bool {
        let special = |s: f64| (s.is_nan(), if s.is_nan() { 0.0 } else { s });
        let (a, b) = (self.clone().canonical(), other.clone().canonical());
        special(self.special) == special(other.special) && (a.lo, a.digits) == (b.lo, b.digits)
    }
}

impl ExactSum {
    /// A sum of nothing (0).
    pub fn new() -> Self {
        Self::default()
    }

    /// Whether it is a sum [`ExactSum::add`] and [`ExactSum::merge`] could have made (one read
    /// from a file): its window inside f64's range of digit positions, every digit within the
    /// bound merging relies on (2⁶²).
    pub fn is_well_formed(&self) -> bool {
        (self.lo as usize).saturating_add(self.digits.len()) <= MAX_POSITIONS
            && self.digits.iter().all(|d| d.unsigned_abs() < 1 << 62)
    }

    /// Adds `x` exactly.
    pub fn add(&mut self, x: f64) {
        if !x.is_finite() {
            self.special += x;
            return;
        }
        if x == 0.0 {
            return;
        }
        let bits = x.to_bits();
        let exponent = ((bits >> 52) & 0x7ff) as u32;
        let fraction = (bits & ((1 << 52) - 1)) as i128;
        // x = m·2^(p − 1074) with m the integer significand.
        let (m, p) = match exponent {
            0 => (fraction, 0),
            e => (fraction | 1 << 52, e - 1),
        };
        let v = if x < 0.0 { -m } else { m } << (p % 32);
        let i = self.cover(p / 32, p / 32 + 3);
        self.digits[i] += (v & 0xffff_ffff) as i64;
        self.digits[i + 1] += ((v >> 32) & 0xffff_ffff) as i64;
        self.digits[i + 2] += (v >> 64) as i64;
        self.adds += 1;
        if self.adds >= ADDS_BEFORE_CARRY {
            self.carry();
        }
    }

    /// Adds another exact sum (exactly), digit by digit: after this sum's carries each of its
    /// digits is below 2³² in magnitude (the top one aside), and the other's below 2⁶² (fewer
    /// than 2³⁰ additions since its last carry), so no digit overflows.
    pub fn merge(&mut self, other: &ExactSum) {
        self.special += other.special;
        if other.digits.is_empty() {
            return;
        }
        self.carry();
        let top = other.lo + other.digits.len() as u32;
        let at = self.cover(other.lo, top);
        for (k, d) in other.digits.iter().enumerate() {
            self.digits[at + k] += d;
        }
        self.carry();
    }

    /// The sum, rounded to the nearest f64 (ties to even; in the subnormal range within one
    /// rounding more). The same exact sum always reads as the same f64.
    pub fn value(&self) -> f64 {
        if self.special != 0.0 || self.special.is_nan() {
            return self.special;
        }
        let mut s = self.clone().canonical();
        let Some(&top_digit) = s.digits.last() else {
            return 0.0;
        };
        let negative = top_digit < 0;
        if negative {
            s.digits.iter_mut().for_each(|d| *d = -*d);
            s = s.canonical();
        }
        let top = s.digits.len() - 1;
        // The top three digits (≥ 65 significant bits when there are three), with a sticky bit
        // for anything below: one correctly rounded conversion.
        let low = top.saturating_sub(2);
        let mut head: u128 = 0;
        for k in (low..=top).rev() {
            head = (head << 32) | s.digits[k] as u128;
        }
        if s.digits[..low].iter().any(|&d| d != 0) {
            head |= 1;
        }
        let exponent = 32 * (s.lo + low as u32) as i32 - 1074;
        let magnitude = head as f64 * pow2(exponent / 2) * pow2(exponent - exponent / 2);
        if negative {
            -magnitude
        } else {
            magnitude
        }
    }

    /// Makes the window reach digit positions `lo..hi` (at least); returns the index of
    /// position `lo` in `digits`. New digits are 0, which keeps the value: a digit is an
    /// integer times its weight wherever it sits (the top one's sign only matters to
    /// [`ExactSum::canonical`]).
    fn cover(&mut self, lo: u32, hi: u32) -> usize {
        if self.digits.is_empty() {
            self.lo = lo;
            self.digits = vec![0; (hi - lo) as usize];
            return 0;
        }
        if lo < self.lo {
            let grow = (self.lo - lo) as usize;
            self.digits.splice(0..0, std::iter::repeat_n(0, grow));
            self.lo = lo;
        }
        let top = self.lo + self.digits.len() as u32;
        if hi > top {
            self.digits
                .resize(self.digits.len() + (hi - top) as usize, 0);
        }
        (lo - self.lo) as usize
    }

    /// Propagates carries: every digit but the top one in [0, 2³²), the top one signed and in
    /// [−2³¹, 2³¹).
    fn carry(&mut self) {
        let Some(last) = self.digits.len().checked_sub(1) else {
            return;
        };
        let mut carry = 0i64;
        for d in &mut self.digits[..last] {
            let t = *d + carry;
            *d = t & 0xffff_ffff;
            carry = t >> 32;
        }
        self.digits[last] += carry;
        // The top digit stays small (a window grows rather than let it overflow).
        while let Some(&top) = self.digits.last() {
            if (-(1i64 << 31)..1 << 31).contains(&top) {
                break;
            }
            let n = self.digits.len() - 1;
            self.digits[n] = top & 0xffff_ffff;
            self.digits.push(top >> 32);
        }
        self.adds = 0;
    }

    /// The unique form of the value: carried (the top digit in [−2³¹, 2³¹)), and no digit that
    /// could be dropped at either end.
    fn canonical(mut self) -> Self {
        self.carry();
        // Drop high digits that only repeat the sign of the one below.
        while self.digits.len() >= 2 {
            let n = self.digits.len();
            let (top, below) = (self.digits[n - 1], self.digits[n - 2]);
            match top {
                0 if below < 1 << 31 => {
                    self.digits.pop();
                }
                -1 if below >= 1 << 31 => {
                    self.digits.pop();
                    self.digits[n - 2] = below - (1 << 32);
                }
                _ => break,
            }
        }
        if self.digits == [0] {
            self.digits.clear();
        }
        // Drop low zero digits.
        let zeros = self.digits.iter().take_while(|&&d| d == 0).count();
        if zeros > 0 && zeros < self.digits.len() {
            self.digits.drain(..zeros);
            self.lo += zeros as u32;
        }
        if self.digits.is_empty() {
            self.lo = 0;
        }
        self
    }
}

/// 2^e for −1022 ≤ e ≤ 1023, exactly.
fn pow2(e: i32) -> f64 {
    f64::from_bits(((e + 1023) as u64) << 52)
}

/// A fixed-point number: an integer count of 2⁻⁶⁴. Sums of them are exact.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct Fixed(pub i128);

impl Fixed {
    /// Zero.
    pub const ZERO: Fixed = Fixed(0);
    /// The largest magnitude [`Fixed::from_f64`] takes: 2⁶², so that 2 such values add
    /// without overflow and a pixel can sum billions of them.
    pub const LIMIT: f64 = 4.611_686_018_427_388e18;

    /// `x` rounded to the nearest 2⁻⁶⁴; None when it is not finite or |x| ≥ [`Fixed::LIMIT`].
    pub fn from_f64(x: f64) -> Option<Fixed> {
        (x.is_finite() && x.abs() < Self::LIMIT).then(|| Fixed((x * 2f64.powi(64)).round() as i128))
    }

    /// The nearest f64.
    pub fn to_f64(self) -> f64 {
        self.0 as f64 * 2f64.powi(-64)
    }
}

impl std::ops::AddAssign for Fixed {
    fn add_assign(&mut self, other: Fixed) {
        self.0 = self.0.saturating_add(other.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// Values m·2^e with |m| < 2⁴⁰ and e in [−60, 20]: their exact sum is an integer count of
    /// 2⁻⁶⁰ that an i128 holds, so the reference is exact.
    fn values(n: usize, seed: u64) -> (Vec<f64>, i128) {
        let mut rng = rand_pcg::Pcg64Mcg::seed_from_u64(seed);
        let mut exact = 0i128;
        let v = (0..n)
            .map(|_| {
                let m: i64 = rng.gen_range(-(1 << 40)..1 << 40);
                let e: i32 = rng.gen_range(-60..=20);
                exact += (m as i128) << (e + 60);
                m as f64 * 2f64.powi(e)
            })
            .collect();
        (v, exact)
    }

    #[test]
    fn sums_exactly_in_any_order_and_grouping() {
        let (v, exact) = values(10_000, 1);
        let reference = exact as f64 * 2f64.powi(-60);
        let mut forward = ExactSum::new();
        v.iter().for_each(|&x| forward.add(x));
        let mut backward = ExactSum::new();
        v.iter().rev().for_each(|&x| backward.add(x));
        // Seven uneven groups merged in reverse order.
        let mut merged = ExactSum::new();
        for part in v.chunks(1_429).rev() {
            let mut s = ExactSum::new();
            part.iter().for_each(|&x| s.add(x));
            merged.merge(&s);
        }
        // i128 → f64 rounds once, to nearest: the reference is the correctly rounded sum.
        assert_eq!(forward.value().to_bits(), reference.to_bits());
        assert_eq!(backward, forward);
        assert_eq!(merged, forward);
        assert_eq!(merged.value().to_bits(), reference.to_bits());
        // A float sum is not order-independent on the same values (why this type exists).
        let f: f64 = v.iter().sum();
        let b: f64 = v.iter().rev().sum();
        assert_ne!(f.to_bits(), b.to_bits());
    }

    #[test]
    fn keeps_what_cancellation_and_extremes_lose() {
        let mut s = ExactSum::new();
        for x in [
            1e300,
            1.0,
            -1e300,
            5e-324,
            -5e-324,
            f64::MAX,
            -f64::MAX,
            3.0,
        ] {
            s.add(x);
        }
        assert_eq!(s.value(), 4.0);
        let mut tiny = ExactSum::new();
        tiny.add(5e-324);
        tiny.add(5e-324);
        assert_eq!(tiny.value(), 1e-323);
        // One float addition of two doubles is correctly rounded: the exact sum reads as it.
        let mut neg = ExactSum::new();
        neg.add(-0.1);
        neg.add(-0.2);
        assert_eq!(neg.value(), -0.1 - 0.2);
        let mut bad = ExactSum::new();
        bad.add(1.0);
        bad.add(f64::INFINITY);
        assert_eq!(bad.value(), f64::INFINITY);
        bad.add(f64::NEG_INFINITY);
        assert!(bad.value().is_nan());
    }

    /// A sum of values of one magnitude keeps a few digits; one spanning the range grows its
    /// window and still sums exactly.
    #[test]
    fn keeps_only_the_digits_its_values_reach() {
        let mut s = ExactSum::new();
        for k in 0..10_000 {
            s.add(1e-9 * (1.0 + k as f64 * 1e-4));
        }
        assert!(s.clone().canonical().digits.len() <= 4, "{s:?}");
        s.add(1e300);
        s.add(-1e300);
        s.add(5e-324);
        s.add(-5e-324);
        let mut t = ExactSum::new();
        for k in (0..10_000).rev() {
            t.add(1e-9 * (1.0 + k as f64 * 1e-4));
        }
        assert_eq!(s, t);
        assert_eq!(s.value(), t.value());
    }

    #[test]
    fn carries_after_many_additions() {
        let mut s = ExactSum::new();
        s.add(1.0);
        s.add(-1.0);
        s.adds = ADDS_BEFORE_CARRY - 10;
        for _ in 0..100 {
            s.add(1e300);
            s.add(-0.5e300);
        }
        assert_eq!(s.value(), 100.0 * 0.5e300);
    }

    #[test]
    fn fixed_point_round_trips_and_refuses_what_it_cannot_hold() {
        assert_eq!(Fixed::from_f64(0.75).unwrap().to_f64(), 0.75);
        let x = 12_345.678_9;
        assert!((Fixed::from_f64(x).unwrap().to_f64() - x).abs() <= 2f64.powi(-64));
        assert_eq!(Fixed::from_f64(f64::NAN), None);
        assert_eq!(Fixed::from_f64(Fixed::LIMIT), None);
        assert!(Fixed::from_f64(-Fixed::LIMIT / 2.0).is_some());
    }
}
