//! From the independent review of the convex checker's bow in the body's
//! frame (2026-11-30, `query::motion`, "Between the ends"): dips. A random
//! slerp (turns up to nearly π) and translation; an obstacle corner whose
//! path seen from the body bulges at a time `t*`; a slab of the body whose
//! face cuts that bulge (poked between `10⁻¹⁰` and nearly all of the room
//! the chord leaves), clear at both ends. Scales from `10⁻¹⁵⁰` to `10¹⁰⁰`,
//! far from the origin too. No motion is called free, and every contact
//! found is exact. Halving the bow, leaving the ball's radius out of `ρ`
//! or halving the translation's term each made the review's run call some
//! of these free.

use dymsum::query::{ConvexUnion, Motion, MotionCheck, MotionChecker};
use dymsum::{DVec3, Polytope, Pose, Rotation};
use dymsum_testkit::{random_rotation, random_unit as unit, rng};
use rand::Rng;
use rand_chacha::ChaCha8Rng;

fn exact_point(from: Pose, to: Pose, t: f64, o: DVec3) -> DVec3 {
    // body-frame image of world point o at time t (float approximation)
    let p = Motion::new(from, to).at(t);
    p.rotation.matrix().transpose() * (o - p.translation)
}

/// One scenario; returns Some(description) on a wrong "Free".
fn scenario(r: &mut ChaCha8Rng, s: f64, offset: f64, stats: &mut [u32; 4]) -> Option<String> {
    let r0 = random_rotation(r);
    let axis = unit(r);
    let theta: f64 = if r.random_bool(0.3) {
        r.random_range(2.5..std::f64::consts::PI - 1e-5)
    } else {
        r.random_range(0.001..2.5)
    };
    let r1 = Rotation::from_axis_angle(axis, theta).unwrap().then(&r0);
    let r1 = if r.random_bool(0.5) {
        r0.then(&Rotation::from_axis_angle(axis, theta).unwrap())
    } else {
        r1
    };
    let base = unit(r) * offset;
    let tscale: f64 = 10f64.powf(r.random_range(-3.0..1.0));
    let t0 = base + unit(r) * s * r.random_range(0.0..3.0);
    let t1 = if r.random_bool(0.2) {
        t0
    } else {
        t0 + unit(r) * s * tscale
    };
    let from = Pose::new(r0, t0);
    let to = Pose::new(r1, t1);
    let motion = Motion::new(from, to);
    let ts: f64 = r.random_range(0.1..0.9);
    let ps = motion.at(ts);
    // a world point: body frame point at t*, radius ~ s * [0.3, 10]
    let zs = unit(r) * s * 10f64.powf(r.random_range(-0.5..1.0));
    let o = ps.rotation.matrix() * zs + ps.translation;
    let (z0, z1) = (exact_point(from, to, 0.0, o), exact_point(from, to, 1.0, o));
    let zs = exact_point(from, to, ts, o);
    let chord = z0 * (1.0 - ts) + z1 * ts;
    let bulge = zs - chord;
    if bulge.length() == 0.0 {
        return None;
    }
    let m = bulge.normalize();
    let room = m.dot(zs) - m.dot(z0).max(m.dot(z1));
    if room.is_nan() || room <= 0.0 {
        return None;
    }
    let f = 10f64.powf(r.random_range(-10.0..-0.05));
    let poke = room * f;
    let k = m.dot(zs) - poke;
    // body slab {x : m.x in [k, k + L]} with lateral extent W
    let e1 = m.any_orthonormal_vector();
    let e2 = m.cross(e1);
    let w = 4.0 * (z0.length().max(z1.length()).max(zs.length())) + s;
    let l = s * 10f64.powf(r.random_range(-1.0..1.0));
    let mut pts = vec![];
    for a in [k, k + l] {
        for b in [-w, w] {
            for c in [-w, w] {
                let v = m * a + e1 * b + e2 * c;
                pts.push([v.x, v.y, v.z]);
            }
        }
    }
    let Ok(slab) = Polytope::from_points(&pts) else {
        return None;
    };
    // spike: tip o, base away from the slab at t* (world -R* m)
    let rs = ps.rotation.matrix();
    let away = rs * (-m);
    let (f1, f2) = (rs * e1, rs * e2);
    let ls = s * 10f64.powf(r.random_range(-1.0..0.5));
    let wd = ls * 10f64.powf(r.random_range(-3.0..-0.5));
    let b0 = o + away * ls;
    let sp = [o, b0 + f1 * wd, b0 - f1 * wd + f2 * wd, b0 - f2 * wd];
    let sp: Vec<[f64; 3]> = sp.iter().map(|v| [v.x, v.y, v.z]).collect();
    let Ok(spike) = Polytope::from_points(&sp) else {
        return None;
    };
    let checker = MotionChecker::new(&ConvexUnion::from(slab), &[ConvexUnion::from(spike)]).ok()?;
    if checker.collides_at(from).ok()? || checker.collides_at(to).ok()? {
        stats[0] += 1;
        return None;
    }
    if !checker.collides_at(ps).ok()? {
        stats[1] += 1;
        return None;
    }
    match checker.check(from, to, 1e-6) {
        Ok(MotionCheck::Free) => Some(format!("FREE but collides at t*={ts}: s={s:e} off={offset:e} theta={theta} f={f:e} poke={poke:e} room={room:e} from={from:?} to={to:?} slab={pts:?} spike={sp:?}")),
        Ok(MotionCheck::Collides { t_contact, .. }) => { stats[2] += 1; if !checker.collides_at(motion.at(t_contact)).unwrap() { return Some(format!("contact not real at {t_contact}")); } None }
        Err(_) => { stats[3] += 1; None }
    }
}

#[test]
fn review_dips_never_free() {
    let mut bad = vec![];
    let mut totals = [0u32; 4];
    let scales = [
        (1.0, 0.0),
        (1e-6, 0.0),
        (1e6, 0.0),
        (1.0, 1e3),
        (1e-3, 1e4),
        (1e-80, 0.0),
        (1e-80, 1e-76),
        (1e80, 0.0),
        (1e-150, 0.0),
        (1e100, 1e104),
        (1.0, 1e8),
    ];
    for (seed, (s, off)) in scales.iter().enumerate() {
        let mut r = rng(1000 + seed as u64);
        let mut stats = [0u32; 4];
        for _ in 0..100 {
            if let Some(msg) = scenario(&mut r, *s, *off, &mut stats) {
                bad.push(msg);
            }
        }
        for (t, x) in totals.iter_mut().zip(stats) {
            *t += x;
        }
    }
    assert!(bad.is_empty(), "{} wrong: {}", bad.len(), bad[0]);
    // Most scenarios are what they say (clear ends, a contact at `t*`)
    // and are decided.
    assert!(totals[2] > 500, "{totals:?}");
}
