//! The inspector's number fields (src/app/panels/number_field.rs): a value is applied only when
//! it is committed (Enter, or the focus leaving the field) and only if the field accepts it; a
//! half-typed number is never applied and a refused one says why. Issue 33: typing 1.5 into a
//! pinned bar's x gave "0.5.433013", 45 into its angle applied 4 degrees first, -1 into a mass
//! became 1e-6 kg. Tested on the field's buffer, then on the widget in a bare egui context.

use bevy_egui::egui;
use rigidlab::app::panels::number_field::{number_field, show, Accepts, NumberField};

const MASS: Accepts = Accepts::above(0.0, 1e9, "kg");
const ANGLE: Accepts = Accepts::closed(-3600.0, 3600.0, "°");

#[test]
fn half_typed_numbers_are_never_applied() {
    // The angle field shows 0; the user types 4, then 45, then presses Enter.
    let mut f = NumberField::default();
    f.sync(0.0);
    assert_eq!(f.text, "0");
    f.typed("4");
    // The scene is drawn again between keys: the text being typed stays.
    f.sync(0.0);
    f.typed("45");
    f.sync(0.0);
    assert_eq!(f.text, "45", "the scene's value overwrote the typing");
    assert_eq!(f.commit(0.0, &ANGLE), Some(45.0));
    // Once applied the field shows the scene's value again, as the scene has it.
    f.sync(45.0);
    assert_eq!(f.text, "45");
    assert!(!f.editing);

    // 1.5 typed over x = 0.433013: each keystroke is text, nothing else.
    let mut x = NumberField::default();
    x.sync(0.433013);
    for t in ["", "1", "1.", "1.5"] {
        x.typed(t);
        x.sync(0.433013);
        assert_eq!(x.text, t);
    }
    assert_eq!(
        x.commit(0.433013, &Accepts::closed(-1e6, 1e6, "m")),
        Some(1.5)
    );
}

#[test]
fn refused_values_say_why_and_apply_nothing() {
    let mut m = NumberField::default();
    m.sync(1.0);
    m.typed("-1");
    assert_eq!(m.commit(1.0, &MASS), None, "a negative mass was applied");
    let why = m.refused.clone().expect("a refusal says why");
    assert!(why.contains("more than 0") && why.contains("kg"), "{why}");
    assert!(
        why.lines().count() == 1 && why.len() < 40,
        "not short: {why:?}"
    );
    // The refused text stays to be fixed; the scene's value does not overwrite it.
    m.sync(1.0);
    assert_eq!(m.text, "-1");
    // Zero is refused too: a mass is more than 0, not clamped to 1e-6 kg.
    m.typed("0");
    assert_eq!(m.commit(1.0, &MASS), None);
    // Escape shows the scene's value again.
    m.cancel(1.0);
    assert_eq!((m.text.as_str(), m.refused.is_none()), ("1", true));

    for (text, accepts, part) in [
        ("0.5.433013", ANGLE, "not a number"),
        ("", ANGLE, "type a number"),
        ("inf", ANGLE, "finite"),
        ("NaN", ANGLE, "finite"),
        ("4000", ANGLE, "at most 3600"),
        ("1.2", Accepts::closed(0.0, 1.0, ""), "at most 1"),
        ("-0.1", Accepts::closed(0.0, 10.0, ""), "at least 0"),
    ] {
        let mut f = NumberField::default();
        f.sync(0.5);
        f.typed(text);
        assert_eq!(f.commit(0.5, &accepts), None, "{text:?} was applied");
        let why = f.refused.unwrap_or_default();
        assert!(why.contains(part), "{text:?}: {why:?}");
    }
    // The range's own ends are accepted where closed.
    assert_eq!(Accepts::closed(0.0, 1.0, "").parse("1"), Ok(1.0));
    assert_eq!(MASS.parse(" 2.5 "), Ok(2.5));
    assert_eq!(MASS.parse("1e-6"), Ok(1e-6));
}

#[test]
fn a_commit_of_the_same_value_is_no_edit() {
    let mut f = NumberField::default();
    f.sync(2.0);
    f.typed("2.000");
    assert_eq!(
        f.commit(2.0, &MASS),
        None,
        "an unchanged value made a step to undo"
    );
    // Not typing: a focus change commits nothing.
    assert_eq!(f.commit(2.0, &MASS), None);
    assert_eq!(show(45.00000000000001), "45");
    assert_eq!(show(-0.0), "0");
    assert_eq!(show(0.25), "0.25");
}

/// One frame of a bare egui context with the field in it; what it committed.
fn frame(ctx: &egui::Context, events: Vec<egui::Event>, value: f64) -> Option<f64> {
    let input = egui::RawInput {
        screen_rect: Some(egui::Rect::from_min_size(
            egui::Pos2::ZERO,
            egui::vec2(400.0, 300.0),
        )),
        events,
        ..Default::default()
    };
    let mut out = None;
    let _ = ctx.run_ui(input, |ui| {
        out = number_field(ui, egui::Id::new("angle"), value, &ANGLE);
    });
    out
}

fn key(key: egui::Key) -> egui::Event {
    egui::Event::Key {
        key,
        physical_key: None,
        pressed: true,
        repeat: false,
        modifiers: Default::default(),
    }
}

#[test]
fn the_widget_applies_on_enter_only() {
    let ctx = egui::Context::default();
    let id = egui::Id::new("angle");
    assert_eq!(frame(&ctx, vec![], 0.0), None);
    ctx.memory_mut(|m| m.request_focus(id));
    assert_eq!(frame(&ctx, vec![], 0.0), None);
    // Select what is there, then type 4 and 5 in two frames: nothing applied.
    let select_all = egui::Event::Key {
        key: egui::Key::A,
        physical_key: None,
        pressed: true,
        repeat: false,
        modifiers: egui::Modifiers::COMMAND,
    };
    assert_eq!(frame(&ctx, vec![select_all.clone()], 0.0), None);
    assert_eq!(frame(&ctx, vec![egui::Event::Text("4".into())], 0.0), None);
    assert_eq!(frame(&ctx, vec![egui::Event::Text("5".into())], 0.0), None);
    assert!(
        ctx.memory(|m| m.has_focus(id)),
        "the field lost its focus while typing"
    );
    // Enter applies 45, once.
    let mut applied = frame(&ctx, vec![key(egui::Key::Enter)], 0.0);
    if applied.is_none() {
        // egui reports the lost focus on the frame after Enter.
        applied = frame(&ctx, vec![], 0.0);
    }
    assert_eq!(applied, Some(45.0));
    assert_eq!(frame(&ctx, vec![], 45.0), None);

    // The focus taken away without Enter (the window drops the text focus when the pointer goes
    // back to the scene): what was typed is committed the next frame, and a refused text stays
    // with its reason.
    ctx.memory_mut(|m| m.request_focus(id));
    frame(&ctx, vec![], 45.0);
    frame(&ctx, vec![select_all.clone()], 45.0);
    assert_eq!(
        frame(&ctx, vec![egui::Event::Text("9x".into())], 45.0),
        None
    );
    ctx.memory_mut(|m| m.stop_text_input());
    assert_eq!(
        frame(&ctx, vec![], 45.0),
        None,
        "a refused value was applied"
    );
    let f: NumberField = ctx.data_mut(|d| d.get_temp(id)).unwrap();
    assert!(
        f.refused
            .as_deref()
            .is_some_and(|w| w.contains("not a number")),
        "{f:?}"
    );
    // Escape drops the typing.
    ctx.memory_mut(|m| m.request_focus(id));
    frame(&ctx, vec![], 45.0);
    frame(&ctx, vec![select_all], 45.0);
    frame(&ctx, vec![egui::Event::Text("7".into())], 45.0);
    assert_eq!(frame(&ctx, vec![key(egui::Key::Escape)], 45.0), None);
    let f: NumberField = ctx.data_mut(|d| d.get_temp(id)).unwrap();
    assert_eq!((f.text.as_str(), f.editing), ("45", false));
}
