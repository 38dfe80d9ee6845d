//! The exercise's hints and worked solution (issue 42), under its questions: hint k appears after
//! the k-th wrong graded answer to the level and stays, numbered "Hint 1 of 3"; the worked
//! solution appears once every question is answered right, or earlier on request, after a
//! confirmation, which marks the solve as "solved with help".

use super::super::ui::rich;
use super::super::view::palette;
use crate::level::Level;
use crate::questions::StudentGrade;
use bevy_egui::egui;
use std::path::{Path, PathBuf};

/// The characters beyond ASCII that egui's default fonts draw, in the window and the web page
/// alike (both use them): what a level's hints and solution may use. Arrows (→ ⇒) and primes
/// (′ ″) are not among them: they draw as boxes; write `->` and `'`. `tests/suite/app/hints.rs`
/// checks each against the fonts, and every level's text against them; docs/levels.md lists them.
pub const SAFE_GLYPHS: &str = "αβγδεζηθικλμνξπρστυφχψωΓΔΘΛΞΠΣΦΨΩ²³¹⁰·×÷−±≈≠≤≥√∞∫∑∂½¼¾°…–—’“”";

/// Where the student is with the level's hints and solution. It follows the level (by file):
/// a run started over keeps it; another level starts it afresh.
#[derive(Debug, Clone, Default)]
pub struct HintState {
    /// The level these counts are for.
    level: Option<PathBuf>,
    /// Wrong graded answers to the level so far (an answer that could not be read is not one).
    pub wrong: usize,
    /// Every question was answered right at once (then the solution shows by itself).
    pub solved: bool,
    /// The solution is shown.
    pub solution_shown: bool,
    /// "Show solution" was pressed before the level was solved: the confirmation is open.
    confirming: bool,
}

impl HintState {
    /// Starts afresh when `file` is not the level the state is for; `help_used` (the shared
    /// `Exercise` flag) goes with it.
    pub fn follow(&mut self, file: &Path, help_used: &mut bool) {
        if self.level.as_deref() != Some(file) {
            *self = HintState {
                level: Some(file.to_path_buf()),
                ..Default::default()
            };
            *help_used = false;
        }
    }

    /// One answer was just graded (`right`, or None when it could not be read); `grades` are
    /// all the level's grades now. A wrong one brings the next hint; all right, the solution.
    pub fn graded(&mut self, right: Option<bool>, grades: &[Option<Result<StudentGrade, String>>]) {
        if right == Some(false) {
            self.wrong += 1;
        }
        let all_right =
            !grades.is_empty() && grades.iter().all(|g| matches!(g, Some(Ok(g)) if g.passed));
        if all_right {
            self.solved = true;
            self.solution_shown = true;
        }
    }

    /// The solution shown on request: before the level is solved it counts as help.
    pub fn reveal(&mut self, help_used: &mut bool) {
        if !self.solved {
            *help_used = true;
        }
        self.solution_shown = true;
        self.confirming = false;
    }

    /// How many of `n` hints are shown: one per wrong answer, all of them at most.
    pub fn shown(&self, n: usize) -> usize {
        self.wrong.min(n)
    }
}

/// The hints shown, as the panel titles them: ("Hint 1 of 3", text), in order.
pub fn shown_hints<'a>(level: &'a Level, st: &HintState) -> Vec<(String, &'a str)> {
    let n = level.hints.len();
    level.hints[..st.shown(n)]
        .iter()
        .enumerate()
        .map(|(i, h)| (format!("Hint {} of {n}", i + 1), h.as_str()))
        .collect()
}

/// Draws the hints shown so far and the solution, or the button that shows it.
pub fn hints(
    ui: &mut egui::Ui,
    level: &Level,
    file: &Path,
    st: &mut HintState,
    help_used: &mut bool,
) {
    st.follow(file, help_used);
    let has_solution = !level.solution.trim().is_empty();
    // The button first: a hint that appears after a wrong answer comes below it and does not
    // move it.
    if has_solution && !st.solution_shown {
        if st.confirming {
            confirm(ui, st, help_used);
        } else if ui.button("Show solution").clicked() {
            if st.solved {
                st.reveal(help_used);
            } else {
                st.confirming = true;
            }
        }
    }
    for (title, text) in shown_hints(level, st) {
        ui.group(|ui| {
            ui.label(rich(title, palette::VELOCITY).strong());
            steps(ui, text);
        });
    }
    if has_solution && st.solution_shown {
        solution(ui, level, st, *help_used);
    }
}

/// The worked solution, one step per line, with whether it came before the answers.
fn solution(ui: &mut egui::Ui, level: &Level, st: &HintState, help_used: bool) {
    ui.group(|ui| {
        ui.label(rich("Worked solution", palette::GRAVITY).strong());
        if help_used && !st.solved {
            ui.label(
                rich(
                    "shown before every answer was right: a solve now counts as solved with help",
                    palette::OUTLINE,
                )
                .small(),
            );
        }
        steps(ui, &level.solution);
    });
}

/// Asks before showing the solution to a level not yet solved.
fn confirm(ui: &mut egui::Ui, st: &mut HintState, help_used: &mut bool) {
    ui.group(|ui| {
        ui.label("Show the worked solution now? Solving the exercise afterwards counts as solved with help.");
        ui.horizontal(|ui| {
            if ui.button("Show it").clicked() {
                st.reveal(help_used);
            }
            if ui.button("Not yet").clicked() {
                st.confirming = false;
            }
        });
    });
}

/// A hint's or solution's text, one step per line, each wrapped to the panel.
fn steps(ui: &mut egui::Ui, text: &str) {
    for line in text.lines().map(str::trim).filter(|l| !l.is_empty()) {
        ui.label(line);
    }
}
