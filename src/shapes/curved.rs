//! Where a curved path (an exact arc, a step's Hermite path) crosses an implicit surface
//! g(x) = 0.

use crate::curve::{Path, RoundSurface};
use glam::DVec3;

/// All arclengths s ∈ (0, length] where the path crosses the plane or sphere `surface`, in
/// order: in closed form on a ray's exact circle ([`crate::curve::CircleArc::crossings`]),
/// else by [`segment_roots`].
pub fn round_roots<P: Path + ?Sized>(seg: &P, length: f64, surface: &RoundSurface) -> Vec<f64> {
    match seg.circle().and_then(|c| c.crossings(surface, length)) {
        Some(found) => found.iter().collect(),
        None => segment_roots(seg, length, |x| surface.implicit(x)),
    }
}

/// All arclengths s ∈ [0, length] where g(x(s)) = 0 along the segment, in order, each refined
/// to ~1e-13 relative.
///
/// The path is cut into pieces short against its curvature (κ·piece ≤ 1/4, at least 4),
/// on which f(s) = g(x(s)) has at most one extremum. A piece whose ends differ in sign holds
/// a root; a piece whose ends share a sign but whose slope f′ = ∇g·t̂ turns toward zero may
/// dip across it twice (a curved path entering and leaving), so its extremum is
/// located by bisection on f′ and tested too.
pub fn segment_roots<P: Path + ?Sized>(
    seg: &P,
    length: f64,
    g: impl Fn(DVec3) -> (f64, DVec3),
) -> Vec<f64> {
    let eval = |s: f64| {
        let p = seg.at(s);
        let (v, grad) = g(p.position);
        (v, grad.dot(p.direction))
    };
    let pieces = ((4.0 * seg.curvature() * length).ceil() as usize).clamp(4, 256);
    let mut roots = Vec::new();
    let mut a = 0.0;
    let (mut fa, mut da) = eval(0.0);
    if fa == 0.0 {
        roots.push(0.0);
    }
    for i in 1..=pieces {
        let b = length * i as f64 / pieces as f64;
        let (fb, db) = eval(b);
        if fa * fb < 0.0 {
            roots.push(refine(&eval, a, b, fa));
        } else if fa != 0.0 && fb != 0.0 && (da * fa.signum() < 0.0) && (db * fa.signum() > 0.0) {
            // f moves toward zero, then away: an extremum in (a, b).
            let m = extremum(&eval, a, b, da);
            let (fm, _) = eval(m);
            if fm * fa <= 0.0 {
                roots.push(refine(&eval, a, m, fa));
                if fm != 0.0 {
                    roots.push(refine(&eval, m, b, fm));
                }
            }
        }
        if fb == 0.0 {
            roots.push(b);
        }
        (a, fa, da) = (b, fb, db);
    }
    roots
}

/// Root of f on [a, b] with f(a) = fa and a sign change: Newton kept inside the bracket,
/// bisection otherwise.
fn refine(eval: &impl Fn(f64) -> (f64, f64), mut a: f64, mut b: f64, fa: f64) -> f64 {
    let up = fa < 0.0;
    let mut s = 0.5 * (a + b);
    for _ in 0..200 {
        let (f, df) = eval(s);
        if f == 0.0 {
            return s;
        }
        if (f > 0.0) == up {
            b = s;
        } else {
            a = s;
        }
        let newton = s - f / df;
        let next = if df != 0.0 && newton > a && newton < b {
            newton
        } else {
            0.5 * (a + b)
        };
        if (next - s).abs() <= 1e-14 * s.abs().max(b) || b - a <= 1e-15 * b {
            return next;
        }
        s = next;
    }
    s
}

/// Where f′ changes sign on [a, b] (f′(a) = da), by bisection.
fn extremum(eval: &impl Fn(f64) -> (f64, f64), mut a: f64, mut b: f64, da: f64) -> f64 {
    for _ in 0..100 {
        let m = 0.5 * (a + b);
        let (_, dm) = eval(m);
        if dm * da > 0.0 {
            a = m;
        } else {
            b = m;
        }
        if b - a <= 1e-15 * b {
            break;
        }
    }
    0.5 * (a + b)
}
