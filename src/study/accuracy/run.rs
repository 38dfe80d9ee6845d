//! Running a study: the error runs (in parallel across levels), then the cost runs (one at a
//! time), then everything written out.

use super::*;

/// The error part of a level's study on rapier (runs in parallel with other levels): the
/// reference, the window and every point's runs, which share the level's budget.
pub fn measure_errors(scene: &Scene, plan: &Plan, tick: &(dyn Fn() + Sync)) -> LevelStudy {
    measure_errors_on(scene, plan, PhysicsEngine::Rapier, tick)
}

/// [`measure_errors`] on `engine` (the scene as `engines::prepared` makes it).
pub fn measure_errors_on(
    scene: &Scene,
    plan: &Plan,
    engine: PhysicsEngine,
    tick: &(dyn Fn() + Sync),
) -> LevelStudy {
    let level = &scene.level;
    let name = level_name(&scene.file);
    let pts = points_on(level, plan, engine);
    let exact = has_exact(level);
    let conserved = metrics::conserved(level);
    let ref_setting = reference_setting(level, plan).on(engine);
    let mut notes = Vec::new();
    let budget = Budget::of(scene, plan, &ref_setting, exact, &mut notes);
    if !engine.is_rapier() {
        // The window is priced for every engine by the run budget's estimate of rapier in f64.
        for n in notes.iter_mut() {
            *n = n.replace(
                "(the f64 reference is estimated at",
                "(priced by rapier's f64 estimate at",
            );
        }
    }
    let windowed = measure::with_duration(scene, budget.window);
    // Questions may be asked at the end: levels with an exact answer run their whole duration.
    let studied = if exact {
        scene.clone()
    } else {
        windowed.clone()
    };
    let reference = measure::reference(&windowed, &ref_setting);
    if let Some(e) = &reference.stopped {
        notes.push(format!(
            "the reference ({}) stopped: {e}; self-consistency uses the {:.3} s before",
            ref_setting.label(),
            reference.duration()
        ));
    }
    let sweep = Sweep {
        scene,
        studied: &studied,
        windowed: &windowed,
        reference: &reference,
        plan,
        budget: &budget,
        conserved,
        exact,
    };
    let mut rows = Vec::new();
    let mut timeable = Vec::new();
    for p in &pts {
        let runs = sweep.runs(&p.setting);
        timeable.push(runs.full.ran && runs.full.stopped.is_none());
        rows.push(sweep.row(&name, p, runs));
        tick();
    }
    if !exact {
        notes.push(format!(
            "no textbook answer or closed-form check: the error is self-consistency against {}",
            if engine.is_rapier() {
                "the f64 reference"
            } else {
                "the engine's own f32 reference"
            }
        ));
    }
    LevelStudy {
        name,
        engine,
        title: level.title.clone(),
        class: class(level),
        scene: studied,
        points: pts,
        rows,
        has_exact: exact,
        conserved,
        notes,
        reference: ref_setting,
        window_s: budget.run_span,
        timeable,
        load: None,
    }
}

/// The reference's setting: f64, and stepping at least 4 times finer than the finest swept dt.
fn reference_setting(level: &level::Level, plan: &Plan) -> Setting {
    let finest = sweep_dts(level, plan)
        .into_iter()
        .fold(level.world.dt, f64::min);
    Setting {
        dt: plan.reference.0.min(finest / 4.0),
        substeps: plan.reference.1,
        iterations: plan.reference.2.max(level.world.solver_iterations),
        precision: Precision::F64,
        all_effects: false,
        engine: PhysicsEngine::Rapier,
    }
}

/// How much of the level a study runs, sized so that the f64 reference fits its budget.
struct Budget {
    /// The cost of one substep at the level's settings, s, as the run budget estimates it
    /// ([`estimated_unit`]).
    unit: f64,
    /// The span the reference and the self-consistency pieces cover, s.
    window: f64,
    /// One self-consistency piece, s.
    piece_s: f64,
    /// The span of each point's full run, s.
    run_span: f64,
    /// The span of the conservation runs, s.
    span: f64,
}

/// One substep at the level's own settings, s, priced by the run budget
/// (`runner::budget::Work::step_us`, a step's estimate over its substeps). An estimate, not a
/// timed probe (until 2026-12-07 a 0.25 s run was timed): the window and the runs left out
/// over the cap then depend on the level alone, not on the machine or how busy it is, so that
/// a sweep split into shards run on different machines (`--shard`) gives the rows a whole run
/// gives.
pub fn estimated_unit(level: &level::Level) -> f64 {
    let base = Setting::of_level(level);
    let opts = crate::sim::Options {
        precision: Some(level::Precision::F32),
        ..base.options()
    };
    let work = crate::runner::budget::Work::of(level, &opts, None);
    // Every step priced split where a spinning ball may split it, as before the run budget's
    // split share (2026-12-07): the study's windows and caps stay those its figures were
    // measured with (docs/accuracy.md).
    // Likewise every coupling at the price of a cable over a pulley, and a `virtual_work`
    // check at a check's, as before the budget told them apart (a later 2026-12-07 change).
    let work = crate::runner::budget::Work {
        split_share: 1.0,
        turning_couplings: work.couplings,
        virtual_work_joints: 0,
        ..work
    };
    work.step_us() * 1e-6 / base.substeps.max(1) as f64
}

impl Budget {
    /// Price a substep at the level's settings, then size the window so that the f64
    /// reference fits its budget. Levels with an exact answer always run their whole duration
    /// (questions may be asked at its end).
    fn of(
        scene: &Scene,
        plan: &Plan,
        ref_setting: &Setting,
        exact: bool,
        notes: &mut Vec<String>,
    ) -> Budget {
        let level = &scene.level;
        let duration = level.world.duration;
        let unit = estimated_unit(level);
        let ref_per_s = measure::predicted(ref_setting, 1.0, unit);
        let piece_s = plan.piece_s.min(duration / 4.0);
        let window = (plan.reference_budget_s / ref_per_s)
            .max(piece_s)
            .min(duration);
        if window < duration {
            notes.push(format!(
                "self-consistency{} over the first {window:.3} s of {duration} s (the f64 reference is estimated at {ref_per_s:.1} s of wall time per simulated second)",
                if exact { "" } else { ", joint drift and cost" }
            ));
        }
        Budget {
            unit,
            window,
            piece_s,
            run_span: if exact { duration } else { window },
            // Light levels run their conservation variant for longer (several periods).
            span: if window < duration {
                window
            } else {
                duration.max(plan.conservation_s)
            },
        }
    }
}

/// What every point of a level's sweep runs against.
struct Sweep<'a> {
    scene: &'a Scene,
    /// The scene of the full runs: the whole level with an exact answer, else the window.
    studied: &'a Scene,
    windowed: &'a Scene,
    reference: &'a measure::Reference,
    plan: &'a Plan,
    budget: &'a Budget,
    conserved: metrics::Conserved,
    exact: bool,
}

/// One point's runs, and what kept them from running or finishing.
struct PointRuns {
    full: measure::FullRun,
    position_error_m: Option<f64>,
    cons: measure::Conservation,
    status: Vec<String>,
}

impl Sweep<'_> {
    /// The full run, the self-consistency pieces and the conservation run at setting s, each
    /// skipped when its predicted time is over the plan's cap.
    fn runs(&self, s: &Setting) -> PointRuns {
        let (plan, budget) = (self.plan, self.budget);
        let mut status = Vec::new();
        let over = |what: &str, t: f64, status: &mut Vec<String>| {
            let over = t > plan.run_cap_s;
            if over {
                status.push(format!(
                    "{what} not run: predicted {t:.1} s > {:.1} s cap",
                    plan.run_cap_s
                ));
            }
            over
        };
        let predicted = |span: f64| measure::predicted(s, span, budget.unit);
        let full = if over("run", predicted(budget.run_span), &mut status) {
            measure::FullRun::default()
        } else {
            measure::full_run(self.studied, s)
        };
        let pos = if over(
            "pieces",
            plan.pieces as f64 * predicted(budget.piece_s),
            &mut status,
        ) {
            Err(String::new())
        } else {
            measure::self_consistency(
                self.windowed,
                s,
                self.reference,
                plan.pieces,
                budget.piece_s,
            )
        };
        let cons = if self.conserved.any()
            && !over("conservation run", predicted(budget.span), &mut status)
        {
            Some(measure::conservation(
                self.scene,
                s,
                self.conserved,
                budget.span,
            ))
        } else {
            None
        };
        if let Some(e) = &full.stopped {
            status.push(format!("run stopped: {e}"));
        }
        if let Err(e) = &pos {
            if !e.is_empty() {
                status.push(format!("piece stopped: {e}"));
            }
        }
        if let Some(e) = cons.as_ref().and_then(|c| c.stopped.clone()) {
            status.push(format!("{} s run stopped: {e}", budget.span));
        }
        PointRuns {
            full,
            position_error_m: pos.ok(),
            cons: cons.unwrap_or_default(),
            status,
        }
    }

    /// The row of accuracy.csv of point p of level `name`.
    fn row(&self, name: &str, p: &Point, runs: PointRuns) -> Row {
        let (s, exact) = (&p.setting, self.exact);
        let PointRuns {
            full,
            position_error_m,
            cons,
            status,
        } = runs;
        let error = if exact {
            match (full.question_error, full.closed_form_error) {
                (Some(a), Some(b)) => Some(a.max(b)),
                (a, b) => a.or(b),
            }
        } else {
            position_error_m
        };
        let knob = if p.baseline {
            "baseline".to_string()
        } else {
            let mut k: Vec<&str> = p.knobs.iter().map(|k| k.name()).collect();
            if p.rapier_default {
                k.push("rapier_default");
            }
            k.join("+")
        };
        Row {
            level: name.to_string(),
            engine: s.engine.name().into(),
            class: class(&self.scene.level).into(),
            knob,
            dt: s.dt,
            dt_label: s.dt_label(),
            substeps: s.substeps,
            pgs_iterations: s.iterations,
            precision: s.precision.name().into(),
            effects: s.effects_name().into(),
            status: if status.is_empty() {
                "ok".into()
            } else {
                status.join("; ")
            },
            window_s: self.budget.run_span,
            error,
            error_kind: if exact {
                "exact_rel".into()
            } else {
                "self_consistency_m".into()
            },
            meets_tolerance: full.meets_tolerance,
            tolerance_ratio: full.tolerance_ratio,
            question_error: full.question_error,
            closed_form_error: full.closed_form_error,
            position_error_m,
            energy_drift_per_s: cons.energy_drift_per_s,
            energy_drift_per_period: cons.energy_drift_per_period,
            energy_gain: cons.energy_drift_per_s.map(|d| d > gain_floor(s.precision)),
            momentum_drift_per_s: cons.momentum_drift_per_s,
            angular_momentum_drift_per_s: cons.angular_momentum_drift_per_s,
            joint_drift_m: full.joint_drift_m,
            cost_us_per_sim_s: None,
            cost_min_us_per_sim_s: None,
            cost_spread: None,
            cost_rounds: None,
        }
    }
}

/// The cost part, one run at a time: `plan.rounds` rounds, each timing every setting of every
/// level once (round-robin), then the median per setting. Settings whose error run was not run
/// (over the cap) or stopped are not timed.
pub fn measure_costs(studies: &mut [LevelStudy], plan: &Plan, tick: &dyn Fn()) {
    let mut samples: Vec<Vec<Vec<f64>>> = studies
        .iter()
        .map(|st| vec![Vec::new(); st.points.len()])
        .collect();
    let mut dead: Vec<Vec<bool>> = studies
        .iter()
        .map(|st| st.timeable.iter().map(|t| !t).collect())
        .collect();
    for _ in 0..plan.rounds {
        for (si, st) in studies.iter().enumerate() {
            for (pi, p) in st.points.iter().enumerate() {
                if !dead[si][pi] {
                    match measure::cost_sample(&st.scene, &p.setting, plan.sample_time) {
                        Some(x) => samples[si][pi].push(x),
                        None => dead[si][pi] = true,
                    }
                }
                tick();
            }
        }
    }
    for (si, st) in studies.iter_mut().enumerate() {
        for (pi, row) in st.rows.iter_mut().enumerate() {
            let mut v = std::mem::take(&mut samples[si][pi]);
            if v.is_empty() || dead[si][pi] {
                continue;
            }
            v.sort_by(f64::total_cmp);
            let median = v[v.len() / 2];
            row.cost_us_per_sim_s = Some(median);
            row.cost_min_us_per_sim_s = Some(v[0]);
            row.cost_spread = Some((v[v.len() - 1] - v[0]) / median);
            row.cost_rounds = Some(v.len());
        }
    }
}

/// Runs the whole study; returns the studies and the files skipped (with why).
pub fn run_study(
    files: &[PathBuf],
    plan: &Plan,
    progress: &ProgressBar,
) -> (Vec<LevelStudy>, Vec<(String, String)>) {
    let (studies, skipped, _) = run_study_timed(files, plan, progress, false);
    (studies, skipped)
}

/// [`run_study`], and with `time_reference` the built-in timing level timed in the same rounds
/// as the levels' settings ([`shard::timing_study`]), so that shards run on different machines
/// can be put on one scale.
pub fn run_study_timed(
    files: &[PathBuf],
    plan: &Plan,
    progress: &ProgressBar,
    time_reference: bool,
) -> (
    Vec<LevelStudy>,
    Vec<(String, String)>,
    Option<shard::TimingRef>,
) {
    let (scenes, skipped) = load_scenes(files, plan, progress);
    let jobs: u64 = scenes
        .iter()
        .map(|(s, e)| (1 + plan.rounds as u64) * points_on(&s.level, plan, *e).len() as u64)
        .sum::<u64>()
        + if time_reference {
            plan.rounds as u64
        } else {
            0
        };
    progress.set_length(jobs);
    progress.set_message("errors (parallel across levels)");
    let tick = || progress.inc(1);
    let mut studies: Vec<LevelStudy> = scenes
        .par_iter()
        .map(|(s, e)| measure_errors_on(s, plan, *e, &tick))
        .collect();
    // Timings only now, one run at a time, so that nothing of ours disturbs them.
    progress.set_message("timing (one run at a time)");
    if time_reference {
        studies.push(shard::timing_study());
    }
    let before = load_average();
    measure_costs(&mut studies, plan, &tick);
    let after = load_average();
    let timing = if time_reference {
        studies.pop().as_ref().and_then(shard::TimingRef::of)
    } else {
        None
    };
    progress.finish_with_message("done");
    if let (Some(b), Some(a)) = (before, after) {
        for st in studies.iter_mut() {
            st.load = Some((b, a));
        }
    }
    (studies, skipped, timing)
}

/// The scenes to sweep, each with its engine, and the files skipped with why.
type Loaded = (Vec<(Scene, PhysicsEngine)>, Vec<(String, String)>);

/// The levels to sweep, each with every engine of the plan that runs it (level order, then the
/// plan's engine order), and the files skipped with why: a level that does not load or has
/// nothing to measure, and a level an engine refuses (named with the engine and the feature).
fn load_scenes(files: &[PathBuf], plan: &Plan, progress: &ProgressBar) -> Loaded {
    let mut skipped = Vec::new();
    let mut scenes = Vec::new();
    for f in files {
        let s = match level::load(f) {
            Ok(s) => s,
            Err(e) => {
                progress.suspend(|| stderr!("{e}"));
                skipped.push((level_name(f), format!("does not load: {}", e.message)));
                continue;
            }
        };
        if let Some(why) = nothing_to_measure(&s.level) {
            skipped.push((level_name(f), why));
            continue;
        }
        for &engine in &plan.engines {
            let mine = engines::prepared(&s, engine);
            match engines::refused(&mine, engine) {
                Some(why) => skipped.push((level_name(f), why)),
                None => scenes.push((mine, engine)),
            }
        }
    }
    (scenes, skipped)
}

/// The machine's 1-minute load average (Linux), to judge how disturbed the timings were.
fn load_average() -> Option<f64> {
    std::fs::read_to_string("/proc/loadavg")
        .ok()?
        .split_whitespace()
        .next()?
        .parse()
        .ok()
}
