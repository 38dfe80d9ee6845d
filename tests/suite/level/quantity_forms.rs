//! A syntax error inside a question's quantity says how that quantity is written (issue 41: the
//! n15 user's `PolarAngle("puck")` got "Expected identifier" and "see docs/levels.md", with no
//! word that it takes `(body:, about:)`; level/quantity_form.rs).

use rigidlab::level::{self, LevelError};
use std::path::Path;

fn refuse(text: &str) -> LevelError {
    match level::parse(Path::new("test.ron"), text) {
        Ok(_) => panic!("accepted:\n{text}"),
        Err(e) => e,
    }
}

fn level_asking(quantity: &str, at: &str) -> String {
    format!(
        "Level(\n  title: \"t\",\n  effects: [gravity],\n  bodies: [\n    (name: \"puck\", shape: Circle(radius: 0.05), mass: 0.3),\n  ],\n  questions: [\n    (id: \"q\", ask: \"?\", unit: \"rad\", expected: 1.0, tolerance: 0.01,\n     quantity: {quantity}, at: {at}),\n  ],\n)\n"
    )
}

/// Each quantity with named fields, written by position as `Speed("puck")` is: the help gives
/// its fields, and the error stays at the offending text (line 8, the question's line).
#[test]
fn a_quantity_written_by_position_gets_its_named_form() {
    let cases = [
        ("PolarAngle(\"puck\")", "PolarAngle(body: .., about: ..)"),
        (
            "ContactForceFrom(\"puck\")",
            "ContactForceFrom(body: .., other: ..",
        ),
    ];
    for (quantity, form) in cases {
        let e = refuse(&level_asking(quantity, "End"));
        assert_eq!(e.line, 9, "{e}");
        assert!(e.help.contains(form), "{quantity}: {e}");
    }
    // Inside an event's `of:` the same.
    let e = refuse(&level_asking(
        "Speed(\"puck\")",
        "Crossing(of: PolarAngle(\"puck\"), value: 1.0)",
    ));
    assert!(e.help.contains("PolarAngle(body: .., about: ..)"), "{e}");
}

/// A quantity written by position (`Speed`) keeps the general help: it has no named form.
#[test]
fn a_positional_quantity_keeps_the_general_help() {
    let e = refuse(&level_asking("Speed(body: \"puck\")", "End"));
    assert!(!e.help.contains("is written"), "{e}");
}
