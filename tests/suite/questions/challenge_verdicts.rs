//! A missed challenge's verdict says which way it missed (issue 42, the student trial of
//! 2026-12-07: "missed by 0.085 m" said nothing of too high or too low): which way the run went
//! where the goal's kind has a way, and which way the control was off, by its name. The ways
//! expected come from each level's closed form (its comment), not from a run: 3% above and below
//! the worked value at the level's own settings.

use rigidlab::level::{self, params::Pick};
use rigidlab::runner;
use std::collections::HashMap;

/// The verdict of the challenge `file` with its control at `k` times its worked value.
fn verdict(file: &str, k: f64) -> String {
    let path = crate::common::repo_path(format!("levels/challenges/{file}"));
    let nominal = level::load_challenge(&path, &Pick::Nominal, None).unwrap();
    let worked = nominal.control.expect("a challenge level").0.worked;
    let loaded = level::load_challenge(&path, &Pick::Nominal, Some(worked * k)).unwrap();
    let (control, value) = loaded.control.clone().expect("a challenge level");
    let r = runner::run_graded(&loaded.scene, &Default::default(), &HashMap::new(), |_| {})
        .unwrap_or_else(|e| panic!("{file}: {e}"));
    let mut c = r.challenge.expect("the report carries the challenge");
    // As `check --answer` and the window's Challenge box do: the run's control and value.
    c.set_control(&control, value, true);
    assert!(!c.success, "{file} at {k} x worked: {c:?}");
    c.verdict()
}

/// Into the cup (a `Reaches` goal): the range is v0^2 / g at 45 degrees, so 3% too fast the
/// path is still 0.115 m above the mouth at x = R, 3% too slow it is 0.126 m below it.
#[test]
fn a_missed_point_says_above_or_below_and_the_control_too_high_or_low() {
    let fast = verdict("projectile_into_cup.ron", 1.03);
    assert!(
        fast.contains("passed above the point: v0 too high"),
        "{fast}"
    );
    let slow = verdict("projectile_into_cup.ron", 0.97);
    assert!(
        slow.contains("passed below the point: v0 too low"),
        "{slow}"
    );
}

/// The bowling ball (an `EndsInside` goal): too much backspin brings it back short of the pins,
/// too little lets it roll on past them (the level's comment derives both).
#[test]
fn a_missed_region_says_past_or_short() {
    let more = verdict("bowling_stop_dead.ron", 1.03);
    assert!(
        more.contains("ended short of the goal: omega0 too high"),
        "{more}"
    );
    let less = verdict("bowling_stop_dead.ron", 0.97);
    assert!(
        less.contains("ended past the goal: omega0 too low"),
        "{less}"
    );
}

/// The spring that stops a block at a mark (a `Reads` goal): the largest extension is
/// v0 sqrt(m / k), so a stiffer spring reads short of the mark's 0.5 m: 0.5 / sqrt(1.03) =
/// 0.4927 m, and a softer one past it, 0.5 / sqrt(0.97) = 0.5077 m (the verdict prints the
/// reading beside the goal's value, which a student can judge whatever the quantity's sign).
#[test]
fn a_missed_reading_says_what_it_read_and_the_goals_value() {
    let stiff = verdict("spring_stops_at_mark.ron", 1.03);
    assert!(
        stiff.contains("read 0.49") && stiff.contains("for the goal's 0.5000: k too high"),
        "{stiff}"
    );
    let soft = verdict("spring_stops_at_mark.ron", 0.97);
    assert!(
        soft.contains("read 0.50") && soft.contains("for the goal's 0.5000: k too low"),
        "{soft}"
    );
}

/// The tethered puck's orbit (a `StaysInside` goal): it may leave its ring on either side, so
/// the run's way is not said; the control's way still is.
#[test]
fn a_region_left_says_no_way_of_its_own() {
    let fast = verdict("tethered_puck_orbit.ron", 1.03);
    assert!(fast.ends_with("m: v0 too high"), "{fast}");
}
