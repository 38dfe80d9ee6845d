//! The exercise's hints and worked solution in the window (issue 42), headless: the left column
//! drawn into a bare egui context at a 1280x800 screen, its buttons clicked where egui drew them.
//! Hint k appears after the k-th wrong answer and stays; "Show solution" asks first and marks the
//! solve as helped; every question right shows the solution without help. And every character
//! of the library's hints and solutions is one egui's default fonts draw (the window and the web
//! page use the same fonts).

use bevy_egui::egui;
use rigidlab::app::panels::hints::SAFE_GLYPHS;
use rigidlab::app::panels::{Browser, Exercise};
use rigidlab::app::{LiveChecks, Run};
use rigidlab::sim::Options;

use crate::common;
use crate::common::app::{all_text, click, left_column, Drawn};

const LEVEL: &str = "levels/momentum/bar_struck_at_percussion.ron";

/// The left column of one level: its run, live checks, browser and the student's exercise.
struct Window {
    ctx: egui::Context,
    phys: Run,
    live: LiveChecks,
    browser: Browser,
    ex: Exercise,
    /// Every text drawn in the last frame, with where.
    texts: Vec<Drawn>,
}

impl Window {
    fn open(file: &str) -> Window {
        let phys = Run::new(common::load(file), Options::default());
        let live = LiveChecks::new(&phys);
        let mut ex = Exercise::default();
        ex.start(phys.sim.level.questions.len());
        let mut w = Window {
            ctx: egui::Context::default(),
            phys,
            live,
            browser: Browser::default(),
            ex,
            texts: Vec::new(),
        };
        w.frame(Vec::new());
        w
    }

    /// One frame with these input events, then one without (egui settles what it measured).
    fn frame(&mut self, events: Vec<egui::Event>) {
        let (phys, live) = (&self.phys, &self.live);
        self.texts = left_column(
            &self.ctx,
            &mut self.browser,
            (phys, live),
            &mut self.ex,
            events,
        );
    }

    /// Clicks the `nth` text drawn exactly as `label` (a button's).
    fn click(&mut self, label: &str, nth: usize) {
        let at = self
            .texts
            .iter()
            .filter(|d| d.text == label)
            .nth(nth)
            .unwrap_or_else(|| panic!("no {label:?} #{nth} drawn: {:?}", self.shown()))
            .rect
            .center();
        self.frame(click(at, true));
        self.frame(click(at, false));
    }

    fn shown(&self) -> Vec<&str> {
        all_text(&self.texts)
    }

    fn shows(&self, text: &str) -> bool {
        self.texts.iter().any(|d| d.text == text)
    }
}

#[test]
fn a_hint_comes_with_each_wrong_answer_and_stays() {
    let mut w = Window::open(LEVEL);
    let hints = w.phys.sim.level.hints.clone();
    assert_eq!(hints.len(), 3);
    assert!(!w.shows("Hint 1 of 3"), "{:?}", w.shown());
    // 2 rad/s for 1.667: wrong (20 % off).
    w.ex.answers[0] = "2".into();
    w.click("Check", 0);
    assert_eq!(w.ex.hints.wrong, 1);
    assert!(
        w.shows("Hint 1 of 3") && w.shows(&hints[0]),
        "{:?}",
        w.shown()
    );
    assert!(
        !w.shows("Hint 2 of 3") && !w.shows(&hints[1]),
        "{:?}",
        w.shown()
    );
    // An answer that cannot be read is not an attempt.
    w.ex.answers[0] = "fast".into();
    w.click("Check", 0);
    assert_eq!(w.ex.hints.wrong, 1);
    // The second wrong answer (to the other question) brings the second hint; the first stays.
    w.ex.answers[1] = "0.6".into();
    w.click("Check", 1);
    assert!(
        w.shows("Hint 1 of 3") && w.shows("Hint 2 of 3"),
        "{:?}",
        w.shown()
    );
    assert!(w.shows(&hints[0]) && w.shows(&hints[1]) && !w.shows(&hints[2]));
    // A third and a fourth: three hints are all there are.
    w.click("Check", 1);
    w.click("Check", 1);
    assert_eq!(w.ex.hints.wrong, 4);
    assert!(w.shows("Hint 3 of 3") && w.shows(&hints[2]));
    assert!(!w.shows("Hint 4 of 3"));
    // The run starting over keeps them; another level starts afresh.
    w.ex.start(2);
    w.frame(Vec::new());
    assert!(w.shows("Hint 3 of 3"), "{:?}", w.shown());
}

#[test]
fn the_solution_on_request_asks_first_and_counts_as_help() {
    let mut w = Window::open(LEVEL);
    let solution = w.phys.sim.level.solution.clone();
    let first_step = solution.lines().next().unwrap().trim().to_string();
    assert!(!w.shows("Worked solution") && !w.shows(&first_step));
    w.click("Show solution", 0);
    // Asked, not yet shown nor counted.
    assert!(!w.ex.help_used && !w.shows(&first_step), "{:?}", w.shown());
    w.click("Not yet", 0);
    assert!(!w.ex.help_used && w.shows("Show solution"));
    w.click("Show solution", 0);
    w.click("Show it", 0);
    assert!(w.ex.help_used);
    assert!(
        w.shows("Worked solution") && w.shows(&first_step),
        "{:?}",
        w.shown()
    );
    // One step per line: every line of the solution is its own label.
    for step in solution.lines().map(str::trim) {
        assert!(w.shows(step), "{step:?} not drawn alone: {:?}", w.shown());
    }
    // Answering right afterwards does not clear the help.
    let expected: Vec<f64> = w
        .phys
        .sim
        .level
        .questions
        .iter()
        .map(|q| q.expected)
        .collect();
    w.ex.answers = expected.iter().map(|v| format!("{v}")).collect();
    w.click("Check", 0);
    w.click("Check", 1);
    assert!(w.ex.hints.solved && w.ex.help_used);
}

#[test]
fn every_question_right_shows_the_solution_without_help() {
    let mut w = Window::open(LEVEL);
    let first_step = w
        .phys
        .sim
        .level
        .solution
        .lines()
        .next()
        .unwrap()
        .trim()
        .to_string();
    let expected: Vec<f64> = w
        .phys
        .sim
        .level
        .questions
        .iter()
        .map(|q| q.expected)
        .collect();
    w.ex.answers = expected.iter().map(|v| format!("{v}")).collect();
    w.click("Check", 0);
    // One of two right: not yet.
    assert!(!w.shows(&first_step), "{:?}", w.shown());
    w.click("Check", 1);
    assert!(
        w.shows("Worked solution") && w.shows(&first_step),
        "{:?}",
        w.shown()
    );
    assert!(!w.ex.help_used && !w.shows("Show solution"));
    assert_eq!(w.ex.hints.wrong, 0);
    assert!(!w.shows("Hint 1 of 3"));
}

/// The glyphs egui's default fonts draw (the proportional family the panels use: Ubuntu Light,
/// then the two emoji fonts). A glyph a font lacks is drawn as a box.
fn drawable(ctx: &egui::Context) -> impl Fn(char) -> bool + '_ {
    let _ = ctx.run_ui(egui::RawInput::default(), |_| {});
    move |c| ctx.fonts_mut(|f| f.has_glyph(&egui::FontId::proportional(14.0), c))
}

#[test]
fn every_safe_glyph_and_every_hint_character_is_drawn() {
    let ctx = egui::Context::default();
    let has = drawable(&ctx);
    let missing: String = SAFE_GLYPHS.chars().filter(|&c| !has(c)).collect();
    assert!(
        missing.is_empty(),
        "not in egui's default fonts: {missing:?}"
    );
    // The check can fail: a glyph egui has no font for (the ✘ the exercise panel gave up).
    assert!(!has('✘'));
    let mut with_help = 0;
    for scene in common::levels_in("levels") {
        let l = &scene.level;
        if l.hints.is_empty() && l.solution.is_empty() {
            continue;
        }
        with_help += 1;
        for text in l.hints.iter().chain(std::iter::once(&l.solution)) {
            for c in text.chars().filter(|c| !c.is_ascii()) {
                assert!(
                    SAFE_GLYPHS.contains(c),
                    "{}: {c:?} (U+{:04X}) is not in the safe set: {text}",
                    scene.file.display(),
                    c as u32
                );
            }
        }
    }
    assert!(with_help >= 1);
}
