//! The per-level plots and summary.md: cheapest setting meeting the tolerance, rapier's
//! defaults, the cost of all effects, and which knob buys accuracy most cheaply.

use super::measure::Precision;
use super::measure::Setting;
use super::plot::{self, Curve, Front, Marker, Panel};
use super::{gain_floor, metrics, Knob, LevelStudy, Plan, Point, Row};
use crate::level::PhysicsEngine;
use std::fmt::Write as _;
use std::path::Path;

/// Errors at or below this are drawn at it and treated as exact.
const FLOOR: f64 = 1e-16;

fn finite(x: Option<f64>) -> Option<f64> {
    x.filter(|v| v.is_finite())
}

/// The points of one knob's curve, in knob order.
fn curve(st: &LevelStudy, k: Knob) -> Vec<(&Point, &Row)> {
    let mut v: Vec<(&Point, &Row)> = st
        .points
        .iter()
        .zip(&st.rows)
        .filter(|(p, _)| p.knobs.contains(&k))
        .collect();
    v.sort_by(|(a, _), (b, _)| {
        let (a, b) = (&a.setting, &b.setting);
        match k {
            Knob::Dt | Knob::DtF64 => b.dt.total_cmp(&a.dt),
            Knob::Substeps => a.substeps.cmp(&b.substeps),
            Knob::Iterations => a.iterations.cmp(&b.iterations),
            Knob::Effects => a.all_effects.cmp(&b.all_effects),
        }
    });
    v
}

pub(super) fn baseline(st: &LevelStudy) -> Option<&Row> {
    st.points
        .iter()
        .zip(&st.rows)
        .find(|(p, _)| p.baseline)
        .map(|(_, r)| r)
}

fn rapier_default(st: &LevelStudy) -> Option<(&Point, &Row)> {
    st.points
        .iter()
        .zip(&st.rows)
        .find(|(p, _)| p.rapier_default || p.setting.same(&Setting::rapier_default()))
}

fn all_effects(st: &LevelStudy) -> Option<&Row> {
    st.points
        .iter()
        .zip(&st.rows)
        .find(|(p, _)| p.setting.all_effects)
        .map(|(_, r)| r)
}

/// Which error a panel shows.
#[derive(Clone, Copy)]
enum Measure {
    /// `Row::error` (exact where the level has an exact answer).
    Primary,
    /// `Row::position_error_m`.
    Position,
}

impl Measure {
    fn of(self, r: &Row) -> Option<f64> {
        finite(match self {
            Measure::Primary => r.error,
            Measure::Position => r.position_error_m,
        })
    }
}

fn panel(st: &LevelStudy, m: Measure, title: &str, y_desc: &str) -> Panel {
    let pt = |r: &Row| -> Option<(f64, f64)> { Some((finite(r.cost_us_per_sim_s)?, m.of(r)?)) };
    let curves = Knob::ALL
        .iter()
        .enumerate()
        .filter(|(_, k)| super::knobs_of(st.engine).contains(k))
        .map(|(i, k)| Curve {
            label: k.label().to_string(),
            color: plot::COLORS[i % plot::COLORS.len()],
            points: curve(st, *k)
                .into_iter()
                .filter_map(|(_, r)| pt(r))
                .collect(),
            marker: Marker::Circle,
        })
        .collect();
    let declared: Vec<(f64, f64)> = st
        .rows
        .iter()
        .filter(|r| r.effects == "declared")
        .map(|r| pt(r).unwrap_or((f64::NAN, f64::NAN)))
        .map(|(c, e)| (c, e.max(FLOOR)))
        .collect();
    let front = metrics::pareto_front(&declared)
        .into_iter()
        .map(|i| declared[i])
        .collect();
    let meets = match m {
        Measure::Primary => st
            .rows
            .iter()
            .filter(|r| r.meets_tolerance == Some(true))
            .filter_map(pt)
            .collect(),
        Measure::Position => Vec::new(),
    };
    let mut marks = Vec::new();
    if let Some(p) = baseline(st).and_then(pt) {
        marks.push(("level".to_string(), p));
    }
    if let Some((p, r)) = rapier_default(st) {
        if !p.baseline {
            if let Some(x) = pt(r) {
                marks.push(("rapier default".to_string(), x));
            }
        } else if let Some(m) = marks.first_mut() {
            m.0 = "level = rapier default".into();
        }
    }
    Panel {
        title: title.to_string(),
        y_desc: y_desc.to_string(),
        curves,
        fronts: vec![Front {
            label: "Pareto front".into(),
            color: plot::FRONT_RAPIER,
            marker: Marker::Circle,
            points: front,
        }],
        meets,
        marks,
        floor: FLOOR,
    }
}

/// One panel of a level's plot over every engine that ran it: each engine's curves and Pareto
/// front, told apart by marker (rapier's circles, Box2D's triangles) and named in the legend;
/// with one engine, that engine's panel as it always was.
fn panel_all(sts: &[&LevelStudy], m: Measure, title: &str, y_desc: &str) -> Panel {
    let mut panels: Vec<(PhysicsEngine, Panel)> = sts
        .iter()
        .map(|st| (st.engine, panel(st, m, title, y_desc)))
        .collect();
    if panels.len() == 1 {
        return panels.remove(0).1;
    }
    let mut out = Panel {
        title: title.to_string(),
        y_desc: y_desc.to_string(),
        curves: Vec::new(),
        fronts: Vec::new(),
        meets: Vec::new(),
        marks: Vec::new(),
        floor: FLOOR,
    };
    for (engine, p) in panels {
        let (marker, front_color) = if engine.is_rapier() {
            (Marker::Circle, plot::FRONT_RAPIER)
        } else {
            (Marker::Triangle, plot::FRONT_BOX2D)
        };
        let e = engine.name();
        out.curves.extend(p.curves.into_iter().map(|c| Curve {
            label: format!("{e}: {}", c.label),
            marker,
            ..c
        }));
        out.fronts.extend(p.fronts.into_iter().map(|f| Front {
            label: format!("Pareto front, {e}"),
            color: front_color,
            marker,
            ..f
        }));
        out.meets.extend(p.meets);
        out.marks
            .extend(p.marks.into_iter().map(|(l, x)| (format!("{l} ({e})"), x)));
    }
    out
}

/// Draws a level's Pareto plot, every engine that ran it on the same axes: the exact error
/// (where there is one) and the self-consistency error.
pub fn plot_level(sts: &[&LevelStudy], path: &Path) -> Result<(), String> {
    let Some(st) = sts.first() else {
        return Err("no study to plot".into());
    };
    let mut panels = Vec::new();
    if st.has_exact {
        panels.push(panel_all(
            sts,
            Measure::Primary,
            "error against the textbook answer",
            "worst relative error (questions, closed form)",
        ));
    }
    panels.push(panel_all(
        sts,
        Measure::Position,
        if sts.len() == 1 && st.engine.is_rapier() {
            "self-consistency against the f64 reference"
        } else {
            "self-consistency against the engine's own fine-step reference"
        },
        "body position error at the end of restarted pieces, m",
    ));
    plot::draw(
        path,
        &format!("{} ({}): error against cost", st.name, st.class),
        &panels,
    )
}

pub(super) fn num(x: Option<f64>) -> String {
    match x {
        Some(0.0) => "0".into(),
        Some(v) if v.is_finite() => {
            if (1e-2..1e4).contains(&v.abs()) {
                format!("{v:.3}")
            } else {
                format!("{v:.2e}")
            }
        }
        Some(_) => "inf".into(),
        None => "-".into(),
    }
}

fn setting_of(r: &Row) -> String {
    format!(
        "dt {} s, {} substeps, {} it., {}{}",
        r.dt_label,
        r.substeps,
        r.pgs_iterations,
        r.precision,
        if r.effects == "all" {
            ", all effects"
        } else {
            ""
        }
    )
}

/// Accuracy bought along one knob's curve, from the level's settings toward more cost.
#[derive(Debug, Clone)]
pub struct KnobGain {
    /// The exponent p of error ~ cost^-p: minus the least-squares slope of ln(error) against
    /// ln(cost) over the level's setting and the curve's dearer points. Higher is cheaper accuracy;
    /// p <= 0: paying buys nothing. None with fewer than two such points or a cost range under
    /// [`MIN_COST_FACTOR`] (indistinguishable from timing noise).
    pub p: Option<f64>,
    /// Error reduction (base / point) and cost increase (point / base) at the dearest point.
    pub finest_error_factor: f64,
    pub finest_cost_factor: f64,
}

/// A cost range below this factor is too small to tell apart from timing noise.
const MIN_COST_FACTOR: f64 = 1.15;

/// The row of the level's own knobs at a precision (the start of the dt curves).
fn base_row<'a>(st: &'a LevelStudy, precision: &str) -> Option<&'a Row> {
    let level = Setting::of_level(&st.scene.level);
    st.points
        .iter()
        .zip(&st.rows)
        .find(|(p, r)| {
            !p.setting.all_effects
                && r.precision == precision
                && (p.setting.dt - level.dt).abs() <= 1e-9 * level.dt
                && p.setting.substeps == level.substeps
                && p.setting.iterations == level.iterations
        })
        .map(|(_, r)| r)
}

fn knob_gain(st: &LevelStudy, k: Knob, m: Measure) -> Option<KnobGain> {
    // The f64 dt curve starts from the level's settings in f64: it measures dt, not precision.
    let base = base_row(st, if k == Knob::DtF64 { "f64" } else { "f32" })?;
    let (cb, eb) = (finite(base.cost_us_per_sim_s)?, m.of(base)?.max(FLOOR));
    let mut pts = vec![(cb, eb)];
    for (_, r) in curve(st, k) {
        let (Some(c), Some(e)) = (finite(r.cost_us_per_sim_s), m.of(r)) else {
            continue;
        };
        if c > cb && !std::ptr::eq(r, base) {
            pts.push((c, e.max(FLOOR)));
        }
    }
    let &(fc, fe) = pts.iter().max_by(|a, b| a.0.total_cmp(&b.0))?;
    let x: Vec<f64> = pts.iter().map(|p| p.0.ln()).collect();
    let y: Vec<f64> = pts.iter().map(|p| p.1.ln()).collect();
    let p = (pts.len() >= 2 && fc >= MIN_COST_FACTOR * cb)
        .then(|| metrics::slope(&x, &y).map(|s| -s))
        .flatten();
    Some(KnobGain {
        p,
        finest_error_factor: eb / fe,
        finest_cost_factor: fc / cb,
    })
}

/// f32 -> f64 at the level's settings: (exact error f32/f64, cost f64/f32, self-consistency f32/f64).
fn precision_ratios(st: &LevelStudy) -> (Option<f64>, Option<f64>, Option<f64>) {
    let (r32, r64) = (base_row(st, "f32"), base_row(st, "f64"));
    let err = |f: fn(&Row) -> Option<f64>| {
        ratio(
            r32.and_then(f).map(|e| e.max(FLOOR)),
            r64.and_then(f).map(|e| e.max(FLOOR)),
        )
    };
    (
        if st.has_exact { err(|r| r.error) } else { None },
        ratio(
            r64.and_then(|r| r.cost_us_per_sim_s),
            r32.and_then(|r| r.cost_us_per_sim_s),
        ),
        err(|r| r.position_error_m),
    )
}

/// The knob families the verdict compares: dt (either precision), substeps, PGS iterations.
const FAMILIES: [(&str, &[Knob]); 3] = [
    ("dt", &[Knob::Dt, Knob::DtF64]),
    ("substeps", &[Knob::Substeps]),
    ("PGS iterations", &[Knob::Iterations]),
];

/// How many points of each knob family make up the level's Pareto front above the level's own
/// cost (declared effects; a point counts once per family it lies on).
fn front_share(st: &LevelStudy, m: Measure) -> [(usize, usize); 3] {
    let mut out = [(0, 0); 3];
    let Some(cb) = baseline(st).and_then(|r| finite(r.cost_us_per_sim_s)) else {
        return out;
    };
    let pts: Vec<(f64, f64)> = st
        .rows
        .iter()
        .map(|r| match (finite(r.cost_us_per_sim_s), m.of(r)) {
            (Some(c), Some(e)) if r.effects == "declared" => (c, e.max(FLOOR)),
            _ => (f64::NAN, f64::NAN),
        })
        .collect();
    let front = metrics::pareto_front(&pts);
    for (i, pt) in pts.iter().enumerate() {
        // NaN costs (runs not timed) are never dearer.
        if pt.0.is_nan() || pt.0 <= cb || st.points[i].baseline {
            continue;
        }
        for (f, (_, knobs)) in FAMILIES.iter().enumerate() {
            if knobs.iter().any(|k| st.points[i].knobs.contains(k)) {
                out[f].1 += 1;
                if front.contains(&i) {
                    out[f].0 += 1;
                }
            }
        }
    }
    out
}

const GAIN_KNOBS: [Knob; 4] = [Knob::Dt, Knob::DtF64, Knob::Substeps, Knob::Iterations];

pub(super) fn median(mut v: Vec<f64>) -> Option<f64> {
    if v.is_empty() {
        return None;
    }
    v.sort_by(f64::total_cmp);
    let n = v.len();
    Some(if n % 2 == 1 {
        v[n / 2]
    } else {
        0.5 * (v[n / 2 - 1] + v[n / 2])
    })
}

/// The cheapest declared-effects setting whose run meets every graded tolerance of the level.
pub(super) fn cheapest_meeting(st: &LevelStudy) -> Option<&Row> {
    st.rows
        .iter()
        .filter(|r| r.effects == "declared" && r.meets_tolerance == Some(true))
        .filter(|r| finite(r.cost_us_per_sim_s).is_some())
        .min_by(|a, b| {
            a.cost_us_per_sim_s
                .unwrap_or(f64::INFINITY)
                .total_cmp(&b.cost_us_per_sim_s.unwrap_or(f64::INFINITY))
        })
}

fn ratio(a: Option<f64>, b: Option<f64>) -> Option<f64> {
    Some(finite(a)? / finite(b)?).filter(|r| r.is_finite())
}

/// summary.md
pub fn markdown(
    studies: &[LevelStudy],
    skipped: &[(String, String)],
    plan: &Plan,
    plots: &[(String, String)],
) -> String {
    let mut s = String::new();
    intro(&mut s, studies, plan);
    cheapest_table(&mut s, studies);
    effects_table(&mut s, studies);
    knob_table(&mut s, studies);
    conservation_table(&mut s, studies, plan);
    level_sections(&mut s, studies, plots);
    super::engine_verdict::section(&mut s, studies, skipped);
    skipped_list(&mut s, skipped);
    s
}

/// "12 level(s)", or "12 level(s) (20 level-engine studies)" when some levels ran on more than
/// one engine.
fn level_count(studies: &[LevelStudy]) -> String {
    let mut names: Vec<&str> = studies.iter().map(|st| st.name.as_str()).collect();
    names.sort_unstable();
    names.dedup();
    if names.len() == studies.len() {
        format!("{} level(s)", names.len())
    } else {
        format!(
            "{} level(s) ({} level-engine studies)",
            names.len(),
            studies.len()
        )
    }
}

/// The title and the method: how errors and costs were measured, and the machine's load.
fn intro(s: &mut String, studies: &[LevelStudy], plan: &Plan) {
    let _ = writeln!(s, "# What accuracy costs in time\n");
    let _ = writeln!(
        s,
        "Generated by `rigidlab study accuracy{}` over {}{}. Method (Erez, Tassa & Todorov 2015): \
         error against the exact (textbook / closed-form) answer where the level has one, and always the \
         self-consistency error against the engine's own f64 run at dt {} s, {} substeps, {} PGS iterations, \
         on {} pieces of {} s restarted from that reference (fresh simulation, body poses and velocities \
         overwritten from the reference state); cost = wall time of stepping per simulated second, median of \
         {} rounds, each timing every setting once, one run at a time (round-robin, on a shared 2-core machine); \
         a round's sample is the fastest of the runs that fit in {} ms (a preempted run is slower, never faster). \
         One knob is varied at a time from each level's settings.\n",
        if plan.quick { " --quick" } else { "" },
        level_count(studies),
        if plan.quick { " (quick sweep: fewer points, coarser reference)" } else { "" },
        super::measure::dt_label(plan.reference.0),
        plan.reference.1,
        plan.reference.2,
        plan.pieces,
        plan.piece_s,
        plan.rounds,
        plan.sample_time.as_millis(),
    );
    let engines: Vec<&str> = studies.iter().fold(Vec::new(), |mut v, st| {
        if !v.contains(&st.engine.name()) {
            v.push(st.engine.name());
        }
        v
    });
    if engines.iter().any(|e| *e != "rapier") {
        let _ = writeln!(
            s,
            "Engines: {} (`--engine`). Box2D v3 runs in f32 only and has no PGS-iterations knob: its sweep \
             is dt, substeps and effects, and its self-consistency reference is its own f32 run at the \
             reference's dt and substeps (rapier's is its f64 build); a level's rows on Box2D are marked \
             [box2d]. Levels an engine refuses are listed at the end with the feature it lacks.\n",
            engines.join(", ")
        );
    }
    if let Some((b, a)) = studies.iter().find_map(|st| st.load) {
        let _ = writeln!(
            s,
            "Machine load (1-minute average, 2 cores) before the timing phase {b:.2}, after {a:.2}: \
             with other work running, single costs scatter by tens of percent (see cost_spread in the CSV); \
             compare ratios and trends, not single numbers.\n"
        );
    }
    let _ = writeln!(
        s,
        "Columns of accuracy.csv: see `Row` in src/study/accuracy.rs. The error of a level is `exact_rel` \
         (worst relative error of its questions and closed-form checks) when it has an exact answer, \
         otherwise `self_consistency_m`. A setting meets the level's tolerance when every graded check and \
         question of the level passes at that setting.\n"
    );
}

/// Table 1: the cheapest setting meeting the tolerance against rapier's defaults.
fn cheapest_table(s: &mut String, studies: &[LevelStudy]) {
    let _ = writeln!(s, "## Cheapest setting that meets each level's tolerance\n");
    let _ = writeln!(
        s,
        "| level | class | level's settings: cost µs/sim s, error | cheapest meeting the tolerance | its cost, error | rapier defaults (1/60 s, 4 substeps, 1 it.): cost, error, meets? | cheapest / defaults cost |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    for st in studies {
        let base = baseline(st);
        let cheap = cheapest_meeting(st);
        let def = rapier_default(st).map(|(_, r)| r);
        let _ = writeln!(
            s,
            "| {} | {} | {}, {} | {} | {}, {} | {}, {}, {} | {} |",
            st.label(),
            st.class,
            num(base.and_then(|r| r.cost_us_per_sim_s)),
            num(base.and_then(|r| r.error)),
            match cheap {
                Some(r) => setting_of(r),
                None if st.rows.iter().all(|r| r.meets_tolerance.is_none()) =>
                    "level grades nothing".into(),
                None => "**none of the swept settings**".into(),
            },
            num(cheap.and_then(|r| r.cost_us_per_sim_s)),
            num(cheap.and_then(|r| r.error)),
            num(def.and_then(|r| r.cost_us_per_sim_s)),
            num(def.and_then(|r| r.error)),
            match def.and_then(|r| r.meets_tolerance) {
                Some(true) => "yes",
                Some(false) => "no",
                None => "-",
            },
            match ratio(
                cheap.and_then(|r| r.cost_us_per_sim_s),
                def.and_then(|r| r.cost_us_per_sim_s)
            ) {
                Some(x) => format!("{x:.2}x"),
                None => "-".into(),
            }
        );
    }
}

/// Table 2: declared effects against all effects.
fn effects_table(s: &mut String, studies: &[LevelStudy]) {
    let _ = writeln!(
        s,
        "\n## Declared effects against all effects (cost at the level's settings)\n"
    );
    let _ = writeln!(
        s,
        "Goal: declared-only at least 2x cheaper than all effects for contact-free scenes (classes `joint` and `contact-free`).\n"
    );
    let _ = writeln!(
        s,
        "| level | class | declared µs/sim s | all effects µs/sim s | all / declared | goal (>= 2x, contact-free) |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|");
    for st in studies {
        let base = baseline(st).and_then(|r| r.cost_us_per_sim_s);
        let all = all_effects(st).and_then(|r| r.cost_us_per_sim_s);
        let r = ratio(all, base);
        let contact_free = !st.class.contains("contact") || st.class == "contact-free";
        let goal = match (contact_free, r) {
            (true, Some(x)) if x >= 2.0 => "met",
            (true, Some(_)) => "**not met**",
            (true, None) => "-",
            (false, _) => "n/a (contacts)",
        };
        let _ = writeln!(
            s,
            "| {} | {} | {} | {} | {} | {} |",
            st.label(),
            st.class,
            num(base),
            num(all),
            r.map_or("-".into(), |x| format!("{x:.2}x")),
            goal
        );
    }
}

/// Table 3: knob gains and the verdict per class.
fn knob_table(s: &mut String, studies: &[LevelStudy]) {
    let _ = writeln!(s, "\n## Which knob buys accuracy most cheaply\n");
    let _ = writeln!(
        s,
        "For each knob, p is the exponent of error ~ cost^-p fitted (least squares, log-log) over the level's \
         setting and the knob's dearer points: higher p = cheaper accuracy, p <= 0 = paying buys nothing, \
         \"-\" = no dearer point or a cost range under {MIN_COST_FACTOR}x (timing noise). The dt (f64) curve starts \
         from the level's settings in f64. \"dearest\" gives error ÷ and cost × at the curve's dearest point. \
         The last column: how many of the knob family's points dearer than the level's settings lie on the Pareto front (self-consistency error; dt counts both precisions). \
         Precision (f32 -> f64 at the level's settings) is listed on its own: error f32/f64 and cost f64/f32.\n"
    );
    let _ = writeln!(
        s,
        "| level | class | knob | p (exact) | dearest: error ÷, cost × (exact) | p (self-consistency) | dearest: error ÷, cost × (self-consistency) | dearer points on the front |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|---|");
    let gain_cell = |g: &Option<KnobGain>| match g {
        Some(g) => (
            g.p.map_or("-".into(), |p| format!("{p:.2}")),
            format!(
                "{} ÷, {:.2} ×",
                num(Some(g.finest_error_factor)),
                g.finest_cost_factor
            ),
        ),
        None => ("-".into(), "-".into()),
    };
    for st in studies {
        let share = front_share(st, Measure::Position);
        for k in GAIN_KNOBS {
            let ge = if st.has_exact {
                knob_gain(st, k, Measure::Primary)
            } else {
                None
            };
            let gp = knob_gain(st, k, Measure::Position);
            let (pe, fe) = gain_cell(&ge);
            let (pp, fp) = gain_cell(&gp);
            let cell = |(a, b): (usize, usize)| format!("{a} of {b}");
            let front = match k {
                Knob::Dt => cell(share[0]),
                Knob::Substeps => cell(share[1]),
                Knob::Iterations => cell(share[2]),
                _ => "(with dt)".to_string(),
            };
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} | {} |",
                st.label(),
                st.class,
                k.label(),
                pe,
                fe,
                pp,
                fp,
                front
            );
        }
        let (e, c, p) = precision_ratios(st);
        let _ = writeln!(
            s,
            "| {} | {} | precision f32 -> f64 | error f32/f64: {} | cost f64/f32: {} | error f32/f64: {} | | |",
            st.label(),
            st.class,
            num(e),
            num(c),
            num(p),
        );
    }
    class_verdicts(s, studies);
}

/// Whether a level's class belongs to a group of scenes.
type Member = fn(&str) -> bool;

/// The verdict's groups per engine: each group of scenes on each engine of the study, named with
/// the engine when the study has more than one (the verdict table extended by engine).
fn engine_groups(
    studies: &[LevelStudy],
    groups: &[(&str, Member)],
) -> Vec<(String, PhysicsEngine, Member)> {
    let mut engines: Vec<PhysicsEngine> = Vec::new();
    for st in studies {
        if !engines.contains(&st.engine) {
            engines.push(st.engine);
        }
    }
    let many = engines.len() > 1;
    engines
        .iter()
        .flat_map(|e| {
            groups.iter().map(move |(g, m)| {
                let name = if many {
                    format!("{g}, {}", e.name())
                } else {
                    g.to_string()
                };
                (name, *e, *m)
            })
        })
        .collect()
}

/// Table 3's second half: per class of scene, which knob family buys accuracy most cheaply.
fn class_verdicts(s: &mut String, studies: &[LevelStudy]) {
    let groups: [(&str, Member); 3] = [
        ("contact scenes", |c| {
            c.contains("contact") && c != "contact-free"
        }),
        ("joint scenes", |c| c.contains("joint")),
        ("contact-free, joint-free scenes", |c| c == "contact-free"),
    ];
    let _ = writeln!(s, "\n### Verdict per class\n");
    let _ = writeln!(
        s,
        "Per knob family: the median p over the class's levels (the dt family uses the f32 dt curve; levels \
         where the knob has a fitted p), and how many of the family's points dearer than the levels' own settings \
         lie on the Pareto front (self-consistency error, summed over the class; dt counts both precisions). \
         Precision: median error ratio f32/f64 and cost ratio f64/f32 at the levels' settings.\n"
    );
    let _ = writeln!(
        s,
        "| class | knob | median p (exact) | levels | median p (self-consistency) | levels | front points |"
    );
    let _ = writeln!(s, "|---|---|---|---|---|---|---|");
    let mut verdicts = Vec::new();
    let groups = engine_groups(studies, &groups);
    for (gname, engine, member) in groups {
        let gname = gname.as_str();
        let members: Vec<&LevelStudy> = studies
            .iter()
            .filter(|st| st.engine == engine && member(st.class))
            .collect();
        if members.is_empty() {
            continue;
        }
        let shares: Vec<[(usize, usize); 3]> = members
            .iter()
            .map(|st| front_share(st, Measure::Position))
            .collect();
        let mut best_e: Option<(&str, f64)> = None;
        let mut best_p: Option<(&str, f64)> = None;
        let mut best_f: Option<(&str, f64)> = None;
        for (f, (fname, knobs)) in FAMILIES.iter().enumerate() {
            let k = knobs[0];
            if !super::knobs_of(engine).contains(&k) {
                continue; // not a knob of this engine's sweep (Box2D: PGS iterations)
            }
            let pe: Vec<f64> = members
                .iter()
                .filter(|st| st.has_exact)
                .filter_map(|st| knob_gain(st, k, Measure::Primary))
                .filter_map(|g| g.p)
                .collect();
            let pp: Vec<f64> = members
                .iter()
                .filter_map(|st| knob_gain(st, k, Measure::Position))
                .filter_map(|g| g.p)
                .collect();
            let on: usize = shares.iter().map(|s| s[f].0).sum();
            let dearer: usize = shares.iter().map(|s| s[f].1).sum();
            let rate = (dearer > 0).then(|| on as f64 / dearer as f64);
            let (ne, np) = (pe.len(), pp.len());
            let (me, mp) = (median(pe), median(pp));
            if let Some(p) = me {
                if best_e.is_none_or(|(_, b)| p > b) {
                    best_e = Some((fname, p));
                }
            }
            if let Some(p) = mp {
                if best_p.is_none_or(|(_, b)| p > b) {
                    best_p = Some((fname, p));
                }
            }
            if let Some(r) = rate {
                if best_f.is_none_or(|(_, b)| r > b) {
                    best_f = Some((fname, r));
                }
            }
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {on} of {dearer}{} |",
                gname,
                fname,
                me.map_or("-".into(), |p| format!("{p:.2}")),
                ne,
                mp.map_or("-".into(), |p| format!("{p:.2}")),
                np,
                rate.map_or(String::new(), |r| format!(" ({:.0} %)", 100.0 * r))
            );
        }
        // Box2D runs in f32 only: no precision row.
        let prec: Vec<(Option<f64>, Option<f64>, Option<f64>)> = if engine.is_rapier() {
            members.iter().map(|st| precision_ratios(st)).collect()
        } else {
            Vec::new()
        };
        let me = median(prec.iter().filter_map(|x| x.0).collect());
        let mc = median(prec.iter().filter_map(|x| x.1).collect());
        let mp = median(prec.iter().filter_map(|x| x.2).collect());
        if engine.is_rapier() {
            let _ = writeln!(
                s,
                "| {} | precision f32 -> f64 | error ÷ {} | | error ÷ {} | | cost × {} |",
                gname,
                num(me),
                num(mp),
                num(mc)
            );
        }
        let say = |b: Option<(&str, f64)>| match b {
            None => "no data".to_string(),
            Some((_, p)) if p <= 0.05 => "no knob (every median p <= 0.05)".to_string(),
            Some((k, p)) => format!("**{k}** (median p = {p:.2})"),
        };
        verdicts.push(format!(
            "- {gname} ({} levels): self-consistency {}; against the exact answer {}; most often on the Pareto front: {}. {}",
            members.len(),
            say(best_p),
            say(best_e),
            best_f.map_or("none".into(), |(k, r)| format!(
                "**{k}** ({:.0} % of its dearer points)",
                100.0 * r
            )),
            if engine.is_rapier() {
                format!(
                    "f64 instead of f32: error ÷ {} (self-consistency), cost × {}.",
                    num(mp),
                    num(mc)
                )
            } else {
                format!("{} runs in f32 only.", engine.name())
            }
        ));
    }
    let _ = writeln!(s);
    for v in verdicts {
        let _ = writeln!(s, "{v}");
    }
}

/// Table 4: energy and momentum drift of the conservative variants.
fn conservation_table(s: &mut String, studies: &[LevelStudy], plan: &Plan) {
    let cons: Vec<&LevelStudy> = studies.iter().filter(|st| st.conserved.any()).collect();
    if !cons.is_empty() {
        let _ = writeln!(s, "\n## Conservation (conservative variants)\n");
        let _ = writeln!(
            s,
            "Energy drift: signed least-squares slope of E = T + V over the peak kinetic energy, over at least {} s \
             (per period where the motion has a regular one). A gain above the round-off floor ({:.0e}/s in f32, \
             {:.0e}/s in f64) is flagged as unphysical. Momentum: slope of the conserved components' deviation over \
             sum m|v|.\n",
            plan.conservation_s,
            gain_floor(Precision::F32),
            gain_floor(Precision::F64)
        );
        let _ = writeln!(
            s,
            "| level | setting | energy drift /s | per period | gain? | momentum drift /s | angular momentum drift /s |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|---|");
        for st in cons {
            for (_, r) in curve(st, Knob::Dt)
                .into_iter()
                .chain(curve(st, Knob::DtF64))
            {
                let _ = writeln!(
                    s,
                    "| {} | {} | {} | {} | {} | {} | {} |",
                    st.label(),
                    setting_of(r),
                    num(r.energy_drift_per_s),
                    num(r.energy_drift_per_period),
                    match r.energy_gain {
                        Some(true) => "**gain (unphysical)**",
                        Some(false) => "no",
                        None => "-",
                    },
                    num(r.momentum_drift_per_s),
                    num(r.angular_momentum_drift_per_s)
                );
            }
        }
    }
}

/// Per level: its settings, notes, plot and every row.
fn level_sections(s: &mut String, studies: &[LevelStudy], plots: &[(String, String)]) {
    let _ = writeln!(s, "\n## Levels\n");
    for st in studies {
        let _ = writeln!(s, "### {} — {} ({})\n", st.label(), st.title, st.class);
        let lvl = &st.scene.level.world;
        let _ = writeln!(
            s,
            "Level settings: dt {} s, {} substeps, {} PGS iterations; studied over {} s. Reference: {}.\n",
            super::measure::dt_label(lvl.dt),
            lvl.substeps,
            lvl.solver_iterations,
            st.window_s,
            st.reference.label()
        );
        for n in &st.notes {
            let _ = writeln!(s, "- note: {n}");
        }
        if let Some((_, f)) = plots.iter().find(|(n, _)| n == &st.name) {
            let _ = writeln!(s, "\n![{}]({f})\n", st.label());
        }
        let _ = writeln!(
            s,
            "| knob | setting | status | error | meets | position error m | joint drift m | energy drift /s | cost µs/sim s |"
        );
        let _ = writeln!(s, "|---|---|---|---|---|---|---|---|---|");
        for r in &st.rows {
            let _ = writeln!(
                s,
                "| {} | {} | {} | {} | {} | {} | {} | {} | {} |",
                r.knob,
                setting_of(r),
                r.status,
                num(r.error),
                match r.meets_tolerance {
                    Some(true) => "yes",
                    Some(false) => "no",
                    None => "-",
                },
                num(r.position_error_m),
                num(r.joint_drift_m),
                num(r.energy_drift_per_s),
                num(r.cost_us_per_sim_s)
            );
        }
        let _ = writeln!(s);
    }
}

/// The levels the study could not run, and why.
fn skipped_list(s: &mut String, skipped: &[(String, String)]) {
    if !skipped.is_empty() {
        let _ = writeln!(s, "## Skipped\n");
        for (n, why) in skipped {
            let _ = writeln!(s, "- {n}: {why}");
        }
    }
}
