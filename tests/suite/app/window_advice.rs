//! Advice in the window beside the checks (issue 29; src/app/advice.rs): a run that ends with a
//! check or question failed gets the cheapest settings that pass (or "none within" with the
//! known gap), searched on a thread while the frames go on, and its button reruns at them.
//! Headless: MinimalPlugins, the physics and the advice's plugin.

use crate::common;

use bevy::app::ScheduleRunnerPlugin;
use bevy::prelude::*;
use bevy::time::TimeUpdateStrategy;
use rigidlab::app::advice::{try_settings, AdvicePlugin, AdviceState, WindowAdvice};
use rigidlab::app::{LiveChecks, PhysicsPlugin, Playback, Run};
use rigidlab::level::Scene;
use rigidlab::report::Advice;
use rigidlab::sim::Options;
use std::time::{Duration, Instant};

fn app(scene: Scene) -> App {
    let mut app = App::new();
    app.add_plugins(MinimalPlugins.set(ScheduleRunnerPlugin::run_loop(Duration::ZERO)))
        .insert_resource(TimeUpdateStrategy::FixedTimesteps(1))
        .add_plugins(PhysicsPlugin {
            scene,
            options: Options::default(),
            paused: false,
        })
        .add_plugins(AdvicePlugin);
    app.update();
    app
}

fn state(app: &App) -> AdviceState {
    app.world().resource::<WindowAdvice>().state.clone()
}

/// Plays the run to the level's end (one step an update), as the window does.
fn play_to_end(app: &mut App) {
    let steps = {
        let w = &app.world().resource::<Run>().sim.level.world;
        (w.duration / app.world().resource::<Run>().sim.dt()).round() as usize
    };
    for _ in 0..steps + 10 {
        app.update();
    }
    assert!(
        app.world().resource::<Run>().at_end(),
        "the run did not end"
    );
    assert!(
        app.world().non_send::<LiveChecks>().checks.is_some(),
        "no results at the end"
    );
}

/// Updates until the advice is ready; the longest update, which is the window's frame: the
/// search must not run inside one.
fn wait_for_advice(app: &mut App) -> (AdviceState, Duration) {
    let started = Instant::now();
    let mut longest = Duration::ZERO;
    loop {
        let t = Instant::now();
        app.update();
        longest = longest.max(t.elapsed());
        let s = state(app);
        if !matches!(s, AdviceState::Searching) {
            return (s, longest);
        }
        // The search is bounded at study::advice::SEARCH_COST_S (2 s) of estimated runs: 60 s
        // is far past any answer.
        assert!(started.elapsed().as_secs() < 60, "the search never ended");
        std::thread::sleep(Duration::from_millis(5));
    }
}

/// tests/newuser/oscillations/pendulum_period_120deg.ron fails its period question at its own settings
/// (1.08e-2 against 5e-3: rapier's soft pin, docs/known-gaps.md) and passes finer
/// (tests/suite/study/advice.rs). The window advises settings, says so beside the checks, the frames
/// go on meanwhile, and the button's rerun passes.
#[test]
fn a_failing_level_gets_settings_that_pass_beside_its_checks_without_freezing() {
    let scene = common::load("tests/newuser/oscillations/pendulum_period_120deg.ron");
    let mut app = app(scene);
    assert_eq!(
        state(&app),
        AdviceState::None,
        "advice before the run ended"
    );
    play_to_end(&mut app);
    let live = app.world().non_send::<LiveChecks>();
    assert!(
        live.answers.as_ref().unwrap().iter().any(|q| !q.passed),
        "the level passed at its own settings: pick another that fails"
    );
    app.update();
    assert_eq!(
        state(&app),
        AdviceState::Searching,
        "the search did not start at the end of a failed run"
    );
    let searching = app.world().resource::<WindowAdvice>().line().unwrap();
    assert!(searching.contains("searching"), "{searching}");
    let (s, longest) = wait_for_advice(&mut app);
    // A frame of the headless app takes well under a millisecond; one run of this level takes
    // about 40 ms and the search 0.3 s or more: a frame under 100 ms ran none of it.
    assert!(
        longest < Duration::from_millis(100),
        "a frame took {longest:?} while the advice was searched"
    );
    let AdviceState::Ready(Advice::Settings {
        settings,
        cost_ratio,
        ..
    }) = s
    else {
        panic!("no settings advised: {s:?}")
    };
    assert!(cost_ratio > 1.0 && cost_ratio <= 32.0, "{cost_ratio}");
    let line = app.world().resource::<WindowAdvice>().line().unwrap();
    assert!(
        line.starts_with("advice: passes at dt") && line.contains("substeps"),
        "{line}"
    );
    assert!(line.contains(&format!("{cost_ratio}x")), "{line}");

    // "run at these settings": the rerun passes, and then there is nothing to advise.
    let rerun = try_settings(app.world().resource::<Run>(), &settings);
    app.world_mut().write_message(rerun);
    app.update();
    // Then Play.
    app.world_mut().resource_mut::<Playback>().paused = false;
    {
        let phys = app.world().resource::<Run>();
        assert_eq!(phys.sim.dt(), settings.dt);
        assert_eq!(phys.sim.substeps(), settings.substeps);
    }
    app.update();
    assert_eq!(state(&app), AdviceState::None, "the old advice stayed");
    play_to_end(&mut app);
    app.update();
    let live = app.world().non_send::<LiveChecks>();
    let failed = live
        .checks
        .iter()
        .flatten()
        .filter(|c| !c.passed)
        .map(|c| c.kind.clone())
        .chain(
            live.answers
                .iter()
                .flatten()
                .filter(|q| !q.passed)
                .map(|q| q.id.clone()),
        )
        .collect::<Vec<_>>();
    assert!(
        failed.is_empty(),
        "failed at the advised settings: {failed:?}"
    );
    assert_eq!(state(&app), AdviceState::None);
}

/// tests/newuser/impacts/n4_12_ball_pinned_bar_gap.ron: rapier's restitution into a pinned bar is 0.754
/// for 0.8 at every setting (docs/known-gaps.md): the window says none within, naming the gap.
#[test]
fn an_engine_limit_says_none_within_and_names_the_known_gap() {
    let mut app = app(common::load(
        "tests/newuser/impacts/n4_12_ball_pinned_bar_gap.ron",
    ));
    play_to_end(&mut app);
    app.update();
    let (s, _) = wait_for_advice(&mut app);
    assert!(
        matches!(s, AdviceState::Ready(Advice::NoneWithin { .. })),
        "{s:?}"
    );
    let adv = app.world().resource::<WindowAdvice>();
    assert!(adv.settings().is_none(), "settings to try where none pass");
    let line = adv.line().unwrap();
    assert!(line.contains("known-gaps"), "{line}");
}
