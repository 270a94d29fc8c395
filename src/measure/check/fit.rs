//! Fitting a hypothesis to a screenshot: P and N by least squares, the plain
//! values and π as 3.14 preferred when they match as well, the variants one
//! change at a time, and the light's position by a pattern search; and
//! [`check_image`], which runs them.

use super::image::{
    direct_pass, errors, largest_difference, measure, predict, predicted, where_off, Alike, Errors,
    Fitted, Hypothesis, ImageCheck, Measured, Setup, Shading, LAB3_SHARE, NONE, PI_314, THRESHOLD,
};
use super::probe::{LightProbe, COARSE_STRIDE, LIGHT_STRIDE};
use super::student::Geometry;
use crate::pipeline::target::unpack;
use crate::pipeline::StageName;
use crate::pipeline::{Frame, Light};
use glam::Vec3;

/// Least squares for P and N over the interior pixels' unclamped channels:
/// `(observed + offset) / 255 = ρ d P + ρ N`, the offset 1/2 for truncated
/// colours. Two passes: the second leaves out what the first misses by more than
/// 3 steps (an edge the hypothesis places differently, a highlight clamped).
pub(super) fn fit_light(
    m: &Measured,
    observed: &Frame,
    truncated: bool,
    rho_squared: bool,
    power: Option<f32>,
    indirect: Option<f32>,
    pixels: Option<&[usize]>,
) -> (f32, f32) {
    let offset = if truncated { 0.5 } else { 0.0 };
    let handout = Shading::handout();
    let mut estimate: Option<(f64, f64)> = None;
    for _ in 0..2 {
        // saa, sab, sbb, say, sby: the normal equations' sums.
        let mut sums = [0.0f64; 5];
        let mut add = |i: usize| {
            let s = m.surface[i];
            if !m.interior[i] || s == NONE {
                return;
            }
            let rho = m.surfaces[s as usize].0;
            let rho = if rho_squared { rho * rho } else { rho }.to_array();
            let o = unpack(observed.color[i]);
            let d = m.direct[i] as f64;
            for k in 0..3 {
                if o[k] == 0 || o[k] == 255 {
                    continue; // clamped: says only "at least" or "at most"
                }
                let b = rho[k] as f64;
                let a = b * d;
                let y = (o[k] as f64 + offset) * (1.0 / 255.0);
                if let Some((p, n)) = estimate {
                    if (a * p + b * n - y).abs() > 3.0 / 255.0 {
                        continue;
                    }
                }
                sums[0] += a * a;
                sums[1] += a * b;
                sums[2] += b * b;
                sums[3] += a * y;
                sums[4] += b * y;
            }
        };
        match pixels {
            Some(listed) => listed.iter().for_each(|&i| add(i)),
            None => (0..observed.color.len()).for_each(&mut add),
        }
        let [saa, sab, sbb, say, sby] = sums;
        // Light is never negative: each unknown is at least 0, and where the
        // free solution has one below, the best on that edge of the quadrant
        // (the other unknown alone) is taken instead.
        let n_alone = |p: f64| ((sby - p * sab) / sbb).max(0.0);
        let p_alone = |n: f64| ((say - n * sab) / saa).max(0.0);
        let residual = |p: f64, n: f64| {
            p * p * saa + 2.0 * p * n * sab + n * n * sbb - 2.0 * p * say - 2.0 * n * sby
        };
        let solved = match (power, indirect) {
            (Some(p), Some(n)) => Some((p as f64, n as f64)),
            (Some(p), None) => (sbb > 0.0).then(|| (p as f64, n_alone(p as f64))),
            (None, Some(n)) => (saa > 0.0).then(|| (p_alone(n as f64), n as f64)),
            (None, None) => {
                let det = saa * sbb - sab * sab;
                let free = (det.abs() > 1e-12 * (saa * sbb).max(1e-300))
                    .then(|| ((say * sbb - sby * sab) / det, (sby * saa - say * sab) / det));
                match free {
                    Some((p, n)) if p >= 0.0 && n >= 0.0 => Some((p, n)),
                    Some(_) if saa > 0.0 && sbb > 0.0 => {
                        let edges = [(0.0, n_alone(0.0)), (p_alone(0.0), 0.0)];
                        edges
                            .into_iter()
                            .min_by(|a, b| residual(a.0, a.1).total_cmp(&residual(b.0, b.1)))
                    }
                    _ => None,
                }
            }
        };
        match solved {
            Some(s) => estimate = Some(s),
            None => break,
        }
    }
    let (p, n) = estimate.unwrap_or((handout.power as f64, handout.indirect as f64));
    (p as f32, n as f32)
}

/// `v` rounded to `decimals` places.
fn round_to(v: f32, decimals: i32) -> f32 {
    let s = 10f32.powi(decimals);
    (v * s).round() / s
}

/// The interior RMSE (0 to 255) of the free fit above which π as 3.14 is not
/// told from π: renders with any set of variants fit within 0.14, one resized
/// to 3/4 leaves 0.25.
const PI_314_SHOWS_BELOW: f64 = 0.2;

/// The shading that best explains `observed` under `m`: each packing, P and N
/// fitted, then the plain values nearby (P to one or two decimals, N to two,
/// and the same with π as 3.14) preferred when they match as many pixels.
pub(super) fn best_shading(
    m: &Measured,
    observed: &Frame,
    lit: bool,
    setup: &Setup,
) -> (Shading, Errors) {
    if !lit {
        let s = Shading::handout();
        return (s, errors(m, observed, false, s));
    }
    let mut best: Option<(Shading, Errors)> = None;
    // The plainest first: each later one must match clearly more pixels.
    for &(rho_squared, truncated) in packings(setup) {
        let (p, n) = fit_light(
            m,
            observed,
            truncated,
            rho_squared,
            setup.power,
            setup.indirect,
            None,
        );
        let fitted = Shading {
            power: p,
            indirect: n,
            rho_squared,
            truncated,
            ..Shading::handout()
        };
        let fitted_errors = errors(m, observed, true, fitted);
        let interior = m.interior.iter().filter(|&&b| b).count();
        // "As many": within 0.05 % of the interior, far less than the share a
        // slightly wrong P or π costs (a few percent) and more than the pixels a
        // fit of 8-bit data can move.
        let slack = (interior / 2000).max(3);
        let mut chosen = (fitted, fitted_errors);
        let mut candidates = Vec::new();
        let nice_n = setup.indirect.unwrap_or(round_to(n, 2));
        let nice = |v: f32, decimals| setup.power.unwrap_or(round_to(v, decimals));
        // π as 3.14 dims the light by 0.05 %, less than 0.13/255: it shows only
        // in an image whose interiors a free fit reproduces within a fraction
        // of a level, not in one resized, nor from a fitted camera (a
        // thousandth of a unit moves the light on a wall near it by as much).
        let shows_314 = setup.edges_exact && fitted_errors.interior_rmse <= PI_314_SHOWS_BELOW;
        let pis: &[f32] = match shows_314 {
            true => &[3.0, PI_314, std::f32::consts::PI],
            false => &[3.0, std::f32::consts::PI],
        };
        for &pi in pis {
            // The power that gives the same light with π coded as `pi`.
            let power = p * pi / std::f32::consts::PI;
            for decimals in [2, 1] {
                candidates.push(Shading {
                    power: nice(power, decimals),
                    indirect: nice_n,
                    pi,
                    rho_squared,
                    truncated,
                });
            }
        }
        // Later candidates are plainer; each one wins if it matches as well. On a
        // resampled image which pixels land within 2/255 is noise, so there its
        // interiors decide.
        let as_good = |e: &Errors, exact: usize, rmse: f64| match setup.resampled {
            true => e.interior_rmse <= rmse + RESAMPLED_TIE,
            false => e.exact + slack >= exact,
        };
        let (mut best_exact, mut best_rmse) = (fitted_errors.exact, fitted_errors.interior_rmse);
        for c in candidates {
            let e = errors(m, observed, true, c);
            best_exact = best_exact.max(e.exact);
            best_rmse = best_rmse.min(e.interior_rmse);
            if as_good(&e, best_exact, best_rmse)
                && as_good(&e, chosen.1.exact, chosen.1.interior_rmse)
            {
                chosen = (c, e);
            }
        }
        let replace = match &best {
            None => true,
            Some((_, e)) => chosen.1.exact > e.exact + slack,
        };
        if replace {
            best = Some(chosen);
        }
    }
    best.expect("two packings tried")
}

/// `h` with P and N fitted for rounded and for truncated colours, unless the
/// setup fixes them, and the better kept: enough to rank hypotheses and light
/// positions. (The plain values and π come later, in [`best_shading`].)
pub(super) fn quick_fit(h: Hypothesis, observed: &Frame, setup: &Setup, light: Vec3) -> Fitted {
    fitted(
        h,
        measure(h, &setup.mesh, &setup.camera, light),
        observed,
        setup,
        light,
    )
}

/// The ways a lit image's colours may be packed, the plainest first, as
/// (ρ twice, truncated): a JPEG's compression hides half a level, so there its
/// colours are taken as rounded.
fn packings(setup: &Setup) -> &'static [(bool, bool)] {
    match setup.lossy {
        true => &[(false, false), (true, false)],
        false => &[(false, false), (false, true), (true, false), (true, true)],
    }
}

/// How much more interior RMSE (0 to 255) a plainer light may have on a resampled
/// image and still be as good: the handout's P = 1.1 and π against P = 1.05 with π
/// as 3 (the same light to 0.04 %) differ by about 0.02; π as 3 at P = 1.1 against
/// the handout's π at P = 1.15 (0.17 % apart) by about 0.1, which still tells them
/// apart.
const RESAMPLED_TIE: f64 = 0.05;

/// The interior RMSE (0 to 255) above which a fit with ρ once is poor enough to
/// try ρ twice: a right hypothesis fits within 1, ρ twice on the box's colours
/// leaves tens.
const RHO_SQUARED_TRIED_ABOVE: f64 = 4.0;

/// [`quick_fit`] of what has been measured.
fn fitted(
    h: Hypothesis,
    measured: Measured,
    observed: &Frame,
    setup: &Setup,
    light: Vec3,
) -> Fitted {
    let mut best: Option<(Shading, Errors)> = None;
    for &(rho_squared, truncated) in packings(setup) {
        if !h.lit() && (truncated || rho_squared) {
            continue;
        }
        // ρ twice only where ρ once leaves the interiors off: this runs for
        // every hypothesis and every light the search tries.
        if rho_squared && best.is_some_and(|(_, b)| b.interior_rmse <= RHO_SQUARED_TRIED_ABOVE) {
            break;
        }
        let shading = if h.lit() {
            let (power, indirect) = fit_light(
                &measured,
                observed,
                truncated,
                rho_squared,
                setup.power,
                setup.indirect,
                None,
            );
            Shading {
                power,
                indirect,
                rho_squared,
                truncated,
                ..Shading::handout()
            }
        } else {
            Shading::handout()
        };
        let e = errors(&measured, observed, h.lit(), shading);
        // ρ twice must explain clearly more: not a tie broken by rounding.
        let margin = if rho_squared { 0.95 } else { 1.0 };
        if best.is_none_or(|(_, b)| e.interior_rmse < b.interior_rmse * margin) {
            best = Some((shading, e));
        }
    }
    let (shading, errors) = best.expect("one packing tried");
    Fitted {
        hypothesis: h,
        shading,
        light,
        errors,
        measured,
    }
}

/// `f` with the light at `light`: only the direct light is drawn again, since
/// which surface each pixel shows does not depend on the light.
pub(super) fn relit(f: &Fitted, observed: &Frame, setup: &Setup, light: Vec3) -> Fitted {
    let mut measured = f.measured.clone();
    measured.direct = direct_pass(f.hypothesis, &setup.mesh, &setup.camera, light);
    fitted(f.hypothesis, measured, observed, setup, light)
}

/// The best of `hypotheses`.
pub(super) fn best_of(
    hypotheses: &[Hypothesis],
    observed: &Frame,
    setup: &Setup,
    light: Vec3,
) -> Fitted {
    let mut best: Option<Fitted> = None;
    for &h in hypotheses {
        let f = quick_fit(h, observed, setup, light);
        if best
            .as_ref()
            .is_none_or(|b| f.better_than(b, setup.edges_exact))
        {
            best = Some(f);
        }
    }
    best.expect("at least one hypothesis")
}

/// How many pixels `candidate` explains better than `current`, and worse: of the
/// pixels where their predictions differ by more than [`THRESHOLD`], those where
/// it is nearer the image, and those where it is farther.
fn explains(current: &Fitted, candidate: &Fitted, observed: &Frame) -> (usize, usize) {
    let (mut better, mut worse) = (0, 0);
    for (i, &o) in observed.color.iter().enumerate() {
        let a = predict(
            &current.measured,
            i,
            current.hypothesis.lit(),
            current.shading,
        );
        let b = predict(
            &candidate.measured,
            i,
            candidate.hypothesis.lit(),
            candidate.shading,
        );
        if a == b {
            continue;
        }
        let (da, db) = (largest_difference(a, o), largest_difference(b, o));
        if da.abs_diff(db) <= THRESHOLD {
            continue;
        }
        better += (db < da) as usize;
        worse += (db > da) as usize;
    }
    (better, worse)
}

/// From `start`, one change at a time while a change explains the image better.
/// The variants leave separate traces (left and top edges, the rows' ends,
/// occlusions, the shade inside), so each one found improves the match on its own.
/// A change is taken only if it explains at least 10 pixels better and three
/// times as many as it explains worse: the right variant explains nearly all the
/// pixels it changes, while with something else wrong (a light elsewhere) a
/// wrong one that happens to lower the error does barely better than chance.
pub(super) fn climb(start: Fitted, observed: &Frame, setup: &Setup) -> Fitted {
    let mut best = start;
    loop {
        let mut next: Option<(Fitted, usize)> = None;
        for h in best.hypothesis.neighbours() {
            let mut f = quick_fit(h, observed, setup, best.light);
            if setup.fit_light && h.lit() {
                // A variant that moves the pixels moves the light that fits
                // them best: each is judged with the light fitted to it.
                f = search_light(observed, setup, f, 0.02, 40);
            }
            let (better, worse) = explains(&best, &f, observed);
            let gain = better.saturating_sub(worse);
            if better >= 10 && better >= 3 * worse && next.as_ref().is_none_or(|(_, g)| gain > *g) {
                next = Some((f, gain));
            }
        }
        match next {
            Some((f, _)) => best = f,
            None => return best,
        }
    }
}

/// How well the light at `light` explains the interiors under `shapes`' surfaces
/// and packing, P and N fitted: the interior RMSE over every [`LIGHT_STRIDE`]th
/// pixel, with the direct light from `probe` (`shapes`' own).
fn light_score(
    probe: &mut LightProbe,
    shapes: &Fitted,
    observed: &Frame,
    setup: &Setup,
    light: Vec3,
) -> f64 {
    probe.light_at(light);
    let m = &probe.measured;
    let (truncated, rho_squared) = (shapes.shading.truncated, shapes.shading.rho_squared);
    let (power, indirect) = fit_light(
        m,
        observed,
        truncated,
        rho_squared,
        setup.power,
        setup.indirect,
        Some(&probe.pixels),
    );
    let shading = Shading {
        power,
        indirect,
        truncated,
        rho_squared,
        ..Shading::handout()
    };
    let (mut sum, mut count) = (0u64, 0u64);
    for &i in &probe.pixels {
        let (a, b) = (
            unpack(predict(m, i, true, shading)),
            unpack(observed.color[i]),
        );
        for k in 0..3 {
            let e = a[k].abs_diff(b[k]) as u64;
            sum += e * e;
        }
        count += 3;
    }
    if count == 0 {
        f64::INFINITY
    } else {
        (sum as f64 / count as f64).sqrt()
    }
}

/// The light's position by Hooke and Jeeves' pattern search: steps along each
/// axis from `first_step` down to 0.0002, at most `max_tries` positions, and
/// after each success a jump along the way the light moved, which follows the
/// long valley a brighter light farther away makes with a dimmer one nearer. P
/// and N are fitted at each position tried.
pub(super) fn search_light(
    observed: &Frame,
    setup: &Setup,
    start: Fitted,
    first_step: f32,
    max_tries: usize,
) -> Fitted {
    let mut probe = LightProbe::of(&start, setup, LIGHT_STRIDE);
    let mut score = |light: Vec3| light_score(&mut probe, &start, observed, setup, light);
    // The best of `from` and its neighbours `step` away along each axis.
    let explore = |from: (Vec3, f64), step: f32, score: &mut dyn FnMut(Vec3) -> f64| {
        let mut best = from;
        for axis in [Vec3::X, Vec3::Y, Vec3::Z] {
            for sign in [1.0, -1.0] {
                let light = best.0 + axis * step * sign;
                let e = score(light);
                if e < best.1 - 1e-9 {
                    best = (light, e);
                    break;
                }
            }
        }
        best
    };
    let first = start.light;
    let mut base = (first, score(first));
    let mut step = first_step;
    let mut budget = max_tries;
    while step >= 2e-4 && budget > 0 {
        let mut next = explore(base, step, &mut score);
        budget = budget.saturating_sub(6);
        if next.1 >= base.1 - 1e-9 {
            step /= 2.0;
            continue;
        }
        // Jump on along the way the light moved while that keeps helping.
        loop {
            let jump = next.0 * 2.0 - base.0;
            base = next;
            let jumped = (jump, score(jump));
            let beyond = explore(jumped, step, &mut score);
            budget = budget.saturating_sub(7);
            if beyond.1 < base.1 - 1e-9 && budget > 0 {
                next = beyond;
            } else {
                break;
            }
        }
    }
    if base.0 == start.light {
        return start;
    }
    relit(&start, observed, setup, base.0)
}

/// Where a search for the light starts: the best of a coarse grid of 125
/// positions over the box and in front of it (5 along each axis), and the
/// given start, so that a light moved far from the handout's is not looked for
/// in the valley next to it. P and N are fitted at each.
fn coarse_light(observed: &Frame, setup: &Setup, start: Fitted) -> (Fitted, f64) {
    let xs = [-0.8, -0.4, 0.0, 0.4, 0.8];
    let ys = [-0.9, -0.5, -0.1, 0.3, 0.7];
    let zs = [-2.0, -1.2, -0.6, 0.0, 0.6];
    let mut probe = LightProbe::of(&start, setup, COARSE_STRIDE);
    let mut best = (
        start.light,
        light_score(&mut probe, &start, observed, setup, start.light),
    );
    for &x in &xs {
        for &y in &ys {
            for &z in &zs {
                let light = Vec3::new(x, y, z);
                let e = light_score(&mut probe, &start, observed, setup, light);
                if e < best.1 {
                    best = (light, e);
                }
            }
        }
    }
    match best.0 == start.light {
        true => (start, best.1),
        false => (relit(&start, observed, setup, best.0), best.1),
    }
}

/// Checks `observed` against every hypothesis `setup` allows.
pub fn check_image(observed: &Frame, setup: &Setup) -> ImageCheck {
    let light = setup.light;
    let stages: Vec<StageName> = match setup.stage {
        Some(s) => vec![s],
        None => StageName::ALL.to_vec(),
    };
    // First the stage (each as the handout draws it, both interpolations for the
    // lit ones), then every variant of that stage.
    let mut first = Vec::new();
    for &s in &stages {
        first.push(Hypothesis::handout(s));
        if s.interpolates() {
            first.push(Hypothesis {
                affine: !s.affine_by_default(),
                ..Hypothesis::handout(s)
            });
        }
    }
    let mut best = best_of(&first, observed, setup, light);
    // The light first: with it elsewhere, every variant's trace is hidden under
    // the difference in shade. Then the variants, each with the light refitted.
    let search = setup.fit_light && best.hypothesis.lit();
    if search {
        // Each lit stage as the handout draws it gets the coarse grid: under the
        // handout's light a moved light can make the wrong one look best.
        let starts = first
            .iter()
            .filter(|h| h.lit() && (h.affine == h.stage.affine_by_default()))
            .map(|&h| quick_fit(h, observed, setup, light))
            .chain(std::iter::once(best));
        best = starts
            .map(|f| coarse_light(observed, setup, f))
            .min_by(|a, b| a.1.total_cmp(&b.1))
            .map(|(f, _)| f)
            .expect("the best so far is among the starts");
        best = search_light(observed, setup, best, 0.1, 300);
        // The grid's best start can be the wrong stage or interpolation, which
        // the search then takes to a light near the right one: from a fitted
        // camera (no climb between them follows) a walked pixel-light view was
        // called Figure 8. Each other lit stage is searched from the light
        // found, and the best kept.
        let (found, searched) = (best.light, best.hypothesis);
        for &h in first.iter().filter(|h| h.lit() && **h != searched) {
            let start = quick_fit(h, observed, setup, found);
            let f = search_light(observed, setup, start, 0.05, 120);
            if f.errors.interior_rmse < best.errors.interior_rmse {
                best = f;
            }
        }
    }
    if setup.edges_exact {
        best = climb(best, observed, setup);
    }
    if search {
        // A position with two decimals, as people write them, wins if it explains
        // the interiors as well (within 0.02 of a step).
        let plain = (best.light * 100.0).round() / 100.0;
        let snapped = relit(&best, observed, setup, plain);
        if snapped.errors.interior_rmse <= best.errors.interior_rmse + 0.02 {
            best = snapped;
        }
    }
    let (shading, fitted_errors) =
        best_shading(&best.measured, observed, best.hypothesis.lit(), setup);
    best.shading = shading;
    best.errors = fitted_errors;
    let stage = best.hypothesis.stage;
    let handout = Hypothesis {
        affine: if stage == StageName::PixelLight {
            best.hypothesis.affine
        } else {
            Hypothesis::handout(stage).affine
        },
        ..Hypothesis::handout(stage)
    };
    // The handout's figure is lit from the handout's light: where the search
    // found it there, the figure is measured from it, not from where it began.
    let handout_light = Light::handout().position;
    let light = match setup.fit_light && best.light == handout_light {
        true => handout_light,
        false => setup.light,
    };
    let handout_measured = measure(handout, &setup.mesh, &setup.camera, light);
    let before = errors(
        &handout_measured,
        observed,
        handout.lit(),
        Shading::handout(),
    );
    let remaining = where_off(&best, observed);
    let expected = predicted(&best.measured, best.hypothesis.lit(), best.shading);
    let lab3 = best.errors.near >= LAB3_SHARE && best.errors.near_drawn >= LAB3_SHARE;
    let alike = match lab3 {
        true => drawn_alike(&best, setup),
        false => None,
    };
    ImageCheck {
        width: observed.width,
        height: observed.height,
        fitted: lab3.then(|| best.clone()),
        closest: best,
        before,
        remaining,
        expected,
        light_searched: setup.fit_light,
        light_searched_in_vain: false,
        lossy: setup.lossy,
        notes: Vec::new(),
        adjusted: false,
        camera: None,
        crop: None,
        alike,
    }
}

/// Filled's or depth's other, when it draws the same image as `best` from
/// `setup`'s camera as far as the check can see ([`Alike`]): no interior
/// pixel differs, and either no pixel at all or the edges are not exact.
fn drawn_alike(best: &Fitted, setup: &Setup) -> Option<Alike> {
    let other = match best.hypothesis.stage {
        StageName::Filled => StageName::Depth,
        StageName::Depth => StageName::Filled,
        _ => return None,
    };
    // The same student's geometry, with or without the depth buffer.
    let hypothesis = Hypothesis {
        geometry: Geometry {
            depth: Hypothesis::handout(other).geometry.depth,
            ..best.hypothesis.geometry
        },
        ..Hypothesis::handout(other)
    };
    let theirs = measure(hypothesis, &setup.mesh, &setup.camera, best.light);
    let ours = &best.measured;
    let mut pixels = 0;
    for i in 0..ours.surface.len() {
        let (a, b) = (
            predict(ours, i, false, best.shading),
            predict(&theirs, i, false, best.shading),
        );
        if a == b {
            continue;
        }
        if ours.interior[i] || theirs.interior[i] {
            return None;
        }
        pixels += 1;
    }
    (pixels == 0 || !setup.edges_exact).then_some(Alike { hypothesis, pixels })
}
