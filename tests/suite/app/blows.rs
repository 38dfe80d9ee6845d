//! The window's record of a level's blows (src/app/blows.rs) against the impulse-momentum
//! solution of a bar of length L pinned at one end and struck at distance h from the pin by P
//! (MK art. 6/4, 6/10): angular impulse about the pin, P h = I_O w' with I_O = m L^2 / 3, and
//! linear impulse, P + R = m w' L / 2, give the pin's impulse on the bar R = P (3 h / (2 L) - 1):
//! zero at the center of percussion h = 2L/3, P/2 along the blow at the tip h = L.

use rigidlab::app::Run;
use rigidlab::level;
use rigidlab::sim::Options;
use std::path::Path;

fn the_blow(file: &str) -> rigidlab::app::blows::Blow {
    let scene = level::load(Path::new(file)).unwrap();
    let mut phys = Run::new(scene, Options::default());
    while phys.blows.is_empty() {
        assert!(
            phys.advance() && !phys.at_end(),
            "{file}: no blow before the level's end"
        );
    }
    assert_eq!(phys.blows.len(), 1);
    phys.blows[0].clone()
}

/// Horizontal blows of P = 3 N s on a 1.2 m, 3 kg bar hanging from its top end. The step's
/// non-impulsive loads (weight, and m w'^2 L/2 dt = 0.047 N s of centripetal pull, both
/// vertical) stay out of the horizontal part; the level's own tolerance (2e-3 of P) bounds
/// the one-substep joint solve.
#[test]
fn the_pins_impulsive_reaction_is_p_times_3h_over_2l_minus_1() {
    for (file, h_over_l) in [
        ("levels/momentum/bar_struck_at_percussion.ron", 2.0 / 3.0),
        ("levels/momentum/bar_struck_below_percussion.ron", 1.0),
    ] {
        let b = the_blow(file);
        let p = b.impulse.x;
        assert!(
            (p - 3.0).abs() < 1e-12 && b.impulse.y == 0.0,
            "{file}: blow {:?}",
            b.impulse
        );
        let pin = b
            .joints
            .iter()
            .find(|j| j.joint == "pin")
            .expect("the pin's share");
        assert!(
            pin.steady.is_some(),
            "{file}: the blow comes after the first step"
        );
        let theory = p * (1.5 * h_over_l - 1.0);
        let got = pin.impulsive().x;
        assert!(
            (got - theory).abs() <= 2e-3 * p,
            "{file}: pin's impulsive reaction {got} N s, theory {theory} N s"
        );
        println!(
            "{file}: pin impulsive {got:.5} N s (theory {theory:.5}), steady {:?}",
            pin.steady
        );
    }
}
