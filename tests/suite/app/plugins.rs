//! The sandbox's plugins against the headless core (feature `app`).

use bevy::app::ScheduleRunnerPlugin;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use rigidlab::app::{PhysicsPlugin, Run};
use rigidlab::level;
use rigidlab::sim::Options;
use rigidlab::snapshot::Snapshot;
use std::collections::HashMap;
use std::path::Path;
use std::time::Duration;

#[derive(Resource, Default)]
struct Recorded(Vec<Snapshot>);

/// Runs after the physics set in every FixedUpdate; keeps each new step's snapshot.
fn record(phys: Res<Run>, mut rec: ResMut<Recorded>) {
    let s = phys.snapshot();
    if s.step > 0 && rec.0.last().is_none_or(|last| last.step != s.step) {
        rec.0.push(s.clone());
    }
}

/// The plugin, headless: MinimalPlugins, one FixedUpdate per `App::update`.
fn headless_app(scene: &level::Scene) -> App {
    let mut app = App::new();
    app.add_plugins(MinimalPlugins.set(ScheduleRunnerPlugin::run_loop(Duration::ZERO)))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
        .add_plugins(PhysicsPlugin {
            scene: scene.clone(),
            options: Options::default(),
            paused: false,
        })
        .init_resource::<Recorded>()
        .add_systems(FixedUpdate, record.after(rigidlab::app::PhysicsStep));
    app
}

/// Runs `file` for 2 s through the plugin and through the core runner and compares every step.
fn same_trajectory(file: &str) {
    let mut scene = level::load(Path::new(file)).unwrap();
    scene.level.world.duration = 2.0;

    let mut core = Vec::new();
    let report = rigidlab::runner::run_scene(&scene, &Options::default(), &HashMap::new(), |s| {
        core.push(s.clone())
    })
    .unwrap();

    let mut app = headless_app(&scene);
    let steps = (2.0 / scene.level.world.dt).round() as usize;
    let step_of = |app: &App| app.world().resource::<Run>().snapshot().step;
    // The first update runs Startup; the fixed clock starts with it (zero elapsed time).
    app.update();
    let mut updates = 0;
    while (step_of(&app) as usize) < steps {
        let before = step_of(&app);
        app.update();
        updates += 1;
        assert_eq!(
            step_of(&app),
            before + 1,
            "{file}: one FixedUpdate per update, one step per FixedUpdate"
        );
        assert!(updates <= steps, "{file}: too many updates");
    }
    // The plugin stops at the level's end, like `rigidlab check`.
    app.update();
    assert_eq!(
        step_of(&app) as usize,
        steps,
        "{file}: the plugin ran past the level's end"
    );
    let phys = app.world().resource::<Run>();
    let mut window = vec![phys.initial.clone()];
    window.extend(app.world().resource::<Recorded>().0.iter().cloned());

    assert_eq!(
        core.len(),
        steps + 1,
        "{file}: the runner took {} steps",
        core.len() - 1
    );
    assert_eq!(window.len(), core.len(), "{file}: every step recorded once");
    // dt is held in f32 by rapier: 2 s to within its rounding (6e-8 relative).
    assert!((window.last().unwrap().time - 2.0).abs() < 1e-6);
    for (w, c) in window.iter().zip(&core) {
        assert_eq!(w.step, c.step);
        for (bw, bc) in w.bodies.iter().zip(&c.bodies) {
            // Bit for bit: the same f64s, not merely close ones.
            let bits = |b: &rigidlab::snapshot::BodyState| {
                [
                    b.com.x,
                    b.com.y,
                    b.angle,
                    b.velocity.x,
                    b.velocity.y,
                    b.omega,
                ]
                .map(f64::to_bits)
            };
            assert_eq!(
                bits(bw),
                bits(bc),
                "{file}: body {} differs at step {}",
                bw.name,
                w.step
            );
        }
        assert_eq!(w, c, "{file}: snapshot differs at step {}", w.step);
    }

    // The checks and questions the window shows at the level's end are the runner's.
    let live = app.world().non_send::<rigidlab::app::LiveChecks>();
    assert_eq!(live.checks.as_ref().unwrap(), &report.checks, "{file}");
    let answers = live.answers.as_ref().unwrap();
    assert_eq!(answers.len(), report.questions.len());
    for (a, r) in answers.iter().zip(&report.questions) {
        assert_eq!(
            a.engine.to_bits(),
            r.engine.to_bits(),
            "{file}: question {}",
            a.id
        );
    }
}

#[test]
fn plugin_steps_match_the_core_runner_bit_for_bit_pendulum() {
    same_trajectory("levels/kinetics/simple_pendulum.ron");
}

#[test]
fn plugin_steps_match_the_core_runner_bit_for_bit_bouncing_ball() {
    same_trajectory("levels/impact/bouncing_ball.ron");
}

/// The free-body diagram the overlay draws for a block sliding down a 30° incline with mu = 0.2:
/// N = m g cos 30 = 16.99 N and F = mu N = 3.398 N up the slope (MK 3/4: equilibrium normal to the
/// slope, Coulomb friction while sliding). Measured 2026-11-27 at t = 0.5 s: N 9.5e-7 and F
/// 8.6e-7 off (f32 impulses, the contact settled long before); bound 1e-5, a 10x margin.
#[test]
fn free_body_diagram_of_a_sliding_block_shows_n_and_mu_n() {
    use rigidlab::app::quantities::{free_body_arrows, ForceKind};
    let scene = level::load(Path::new("levels/kinetics/incline_friction.ron")).unwrap();
    let mut phys = Run::new(scene, Options::default());
    let mut prev = phys.snapshot().clone();
    while phys.snapshot().time < 0.5 {
        prev = phys.snapshot().clone();
        assert!(phys.advance());
    }
    let s = phys.snapshot();
    let i = s.body_index("block").unwrap();
    let (forces, _) = free_body_arrows(Some(&prev), s, i);
    let sum = |k: ForceKind| -> glam::DVec2 {
        forces.iter().filter(|f| f.kind == k).map(|f| f.force).sum()
    };
    let (m, g, th, mu) = (2.0, 9.81, 30f64.to_radians(), 0.2);
    let normal = sum(ForceKind::ContactNormal);
    let friction = sum(ForceKind::Friction);
    let weight = sum(ForceKind::Gravity);
    let n_exp = m * g * th.cos();
    assert!(
        (normal.length() - n_exp).abs() / n_exp < 1e-5,
        "N = {normal}, expected {n_exp}"
    );
    assert!(
        (friction.length() - mu * n_exp).abs() / (mu * n_exp) < 1e-5,
        "F = {friction}"
    );
    // Exact up to rapier's f32 gravity (-9.81 rounds to -9.8100004).
    assert!(
        (weight - glam::DVec2::new(0.0, -m * g)).length() < 1e-6 * m * g,
        "mg = {weight}"
    );
    // N is normal to the slope (along (-sin 30, cos 30)), F points up the slope (cos 30, sin 30).
    let up_slope = glam::DVec2::new(th.cos(), th.sin());
    assert!(normal.normalize().dot(up_slope).abs() < 1e-3);
    assert!(friction.normalize().dot(up_slope) > 0.999);
}

/// A saved scene loads back identically, also after a body was spawned and the run went on.
#[test]
fn saved_scene_loads_back_identically() {
    let scene = level::load(Path::new("levels/kinetics/simple_pendulum.ron")).unwrap();
    let mut phys = Run::new(scene, Options::default());
    for _ in 0..20 {
        assert!(phys.advance());
    }
    let dir = std::env::temp_dir().join(format!("rigidlab-app-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("saved.ron");
    let expected = rigidlab::editor::capture(&phys.scene.level, phys.snapshot());
    let moment = level::Scene {
        file: phys.scene.file.clone(),
        level: expected.clone(),
    };
    rigidlab::app::user_files::save_level(&moment, &path).unwrap();
    let back = level::load(&path).unwrap();
    assert_eq!(back.level, expected);
    // The captured state is the current one: the bob's pose and velocity, exactly.
    let bob = phys.snapshot().body_index("bob").unwrap();
    let b = &phys.snapshot().bodies[bob];
    let def = &back.level.bodies[bob];
    assert_eq!(def.position, (b.position.x, b.position.y));
    assert_eq!(def.velocity, (b.velocity.x, b.velocity.y));
    assert_eq!(def.omega, b.omega);
    // And a new run from it starts where this one is.
    let restarted = rigidlab::sim::Simulation::new(&back, &Options::default());
    let r = &restarted.snapshot().bodies[bob];
    assert!((r.com - b.com).length() < 1e-6, "{} vs {}", r.com, b.com);
    std::fs::remove_dir_all(&dir).ok();
}

/// A typed answer is graded with the level's tolerance.
#[test]
fn typed_answers_are_graded_against_the_expected_value() {
    let scene = level::load(Path::new("levels/kinetics/simple_pendulum.ron")).unwrap();
    let q = &scene.level.questions[0]; // v = sqrt(g L) = 3.1321 m/s, tolerance 0.5 %
    let g = rigidlab::app::panels::grade(q, "3.13").unwrap();
    assert!(g.passed && g.rel_error < 1e-3, "{g:?}");
    let g = rigidlab::app::panels::grade(q, " 3,2 ").unwrap();
    assert!(!g.passed, "3.2 is 2 % off");
    assert!(rigidlab::app::panels::grade(q, "fast").is_err());
    assert!(rigidlab::app::panels::grade(q, "inf").is_err());
}

/// Renders the pendulum through the real renderer (no window: an image target) and checks the PNG:
/// the bob's fill color is there, centered where the core puts the bob at that time.
#[test]
fn render_shows_the_bob_where_the_core_puts_it() {
    use rigidlab::app::render::{render_frame, vulkan_check, RenderOptions};
    if let Err(why) = vulkan_check() {
        // CI sets RIGIDLAB_REQUIRE_RENDER once it has installed Xvfb and Mesa: there a skip is a failure.
        assert!(
            std::env::var_os("RIGIDLAB_REQUIRE_RENDER").is_none(),
            "the render test cannot run: {why}"
        );
        println!("skipped: {why}");
        return;
    }
    let scene = level::load(Path::new("levels/kinetics/simple_pendulum.ron")).unwrap();
    let t = 0.4;
    let dir = std::env::temp_dir().join(format!("rigidlab-render-test-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("pendulum.png");
    let opts = RenderOptions::default();
    render_frame(&scene, t, Some(&out), &opts).unwrap();

    let bytes = std::fs::read(&out).unwrap();
    let img = bevy::image::Image::from_buffer(
        &bytes,
        bevy::image::ImageType::Extension("png"),
        bevy::image::CompressedImageFormats::NONE,
        true,
        bevy::image::ImageSampler::Default,
        bevy::asset::RenderAssetUsages::default(),
    )
    .unwrap();
    assert_eq!((img.width(), img.height()), (opts.width, opts.height));

    // Where the bob should be: the core's state at t, through the view's fit.
    let mut phys = Run::new(scene.clone(), Options::default());
    for _ in 0..(t / phys.sim.dt()).round() as u64 {
        assert!(phys.advance());
    }
    let bob = phys.snapshot().bodies[1].com;
    let mut view = rigidlab::app::view::View {
        viewport: Rect::new(0.0, 0.0, opts.width as f32, opts.height as f32),
        ..Default::default()
    };
    view.fit_to(&rigidlab::app::view::motion_bounds(
        &scene,
        &Options::default(),
    ));
    let expect = view.to_screen(bob);
    let radius_px = 0.05 / view.m_per_px;

    // Pixels of the dynamic-body fill (within 3/255 per channel), and their centroid.
    let fill = rigidlab::app::view::palette::DYNAMIC.to_srgba();
    let want = [fill.red, fill.green, fill.blue].map(|c| (c * 255.0).round() as i32);
    let (mut n, mut sx, mut sy, mut other) = (0usize, 0.0, 0.0, 0usize);
    let bg = rigidlab::app::view::palette::BACKGROUND.to_srgba();
    let bgc = [bg.red, bg.green, bg.blue].map(|c| (c * 255.0).round() as i32);
    for y in 0..img.height() {
        for x in 0..img.width() {
            let p = img.pixel_bytes(UVec3::new(x, y, 0)).unwrap();
            let c = [p[0] as i32, p[1] as i32, p[2] as i32];
            if c.iter().zip(&want).all(|(a, b)| (a - b).abs() <= 3) {
                n += 1;
                sx += x as f64;
                sy += y as f64;
            } else if c.iter().zip(&bgc).any(|(a, b)| (a - b).abs() > 3) {
                other += 1;
            }
        }
    }
    let disc = std::f64::consts::PI * radius_px * radius_px;
    // The fill shows most of the disc (lines and arrows drawn over it hide some of it).
    assert!(
        n as f64 > 0.5 * disc && (n as f64) < 1.2 * disc,
        "{n} fill pixels, disc of {disc:.0}"
    );
    let c = (sx / n as f64, sy / n as f64);
    assert!(
        (c.0 - expect.x as f64).abs() < 3.0 && (c.1 - expect.y as f64).abs() < 3.0,
        "bob at {c:?}, expected {expect}"
    );
    // Lines, arrows and labels were drawn too.
    assert!(other > 2000, "only {other} drawn pixels besides the bob");
    println!(
        "rendered {} ({n} bob pixels at {c:?}, {other} other drawn pixels)",
        out.display()
    );
    std::fs::remove_dir_all(&dir).ok();
}

/// The solver panel's error is the accuracy study's figure for the same settings: the worst
/// relative error of the questions and closed-form checks, and the worst error / tolerance
/// (src/study/accuracy/measure.rs `full_run`). Same simulation, same probes: equal to the bit.
#[test]
fn solver_panel_error_is_the_accuracy_studys_figure() {
    use rigidlab::study::accuracy::measure::{full_run, Setting};
    for (file, dt_div, substeps) in [
        ("levels/kinematics/free_fall.ron", 1.0, None),
        ("levels/energy/block_friction_work.ron", 1.0, None),
        // Settings changed in the panel: dt / 2 and 8 substeps.
        ("levels/energy/block_friction_work.ron", 2.0, Some(8)),
    ] {
        let scene = level::load(Path::new(file)).unwrap();
        let mut setting = Setting::of_level(&scene.level);
        setting.dt /= dt_div;
        if let Some(n) = substeps {
            setting.substeps = n;
        }
        let mut phys = Run::new(scene.clone(), setting.options());
        let mut live = rigidlab::app::LiveChecks::new(&phys);
        while !phys.at_end() {
            assert!(phys.advance(), "{file}: {:?}", phys.error);
            live.observe(&phys);
        }
        let (error, ratio) = rigidlab::app::panels::study_error(
            live.checks.as_ref().unwrap(),
            live.answers.as_ref().unwrap(),
        );
        let study = full_run(&scene, &setting);
        let expected = match (study.question_error, study.closed_form_error) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
        assert!(expected.is_some(), "{file}: the level has an exact answer");
        assert_eq!(
            error.map(f64::to_bits),
            expected.map(f64::to_bits),
            "{file}"
        );
        assert_eq!(
            ratio.map(f64::to_bits),
            study.tolerance_ratio.map(f64::to_bits),
            "{file}"
        );
    }
}
