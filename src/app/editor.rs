//! The scene editor in the window: [`EditorCommand`] messages (from the editor panel and the
//! mouse tools, or from a test) applied through the core's [`crate::editor`], with undo and redo.
//!
//! Every edit changes the scene as it starts (t = 0) and the run starts over from it, paused, with
//! the camera left where the user put it; an edit the validator refuses leaves the scene as it was
//! and says why in the panel.

use super::physics::PhysicsCommand;
use super::run::Run;
use crate::editor::{self, Edit, History, NewShape};
use crate::level::{JointKind, QuestionDef, Scene};
use crate::questions::QuestionResult;
use crate::runner::{self, Estimate, Mode};
use crate::sim::Options;
use bevy::prelude::*;
use glam::DVec2;
use std::path::PathBuf;

/// What the editor is asked to do.
#[derive(Message, Debug, Clone, PartialEq)]
pub enum EditorCommand {
    Apply(Edit),
    Undo,
    Redo,
    /// A new scene: a ground line and nothing else.
    New,
    /// Writes the scene as a level file (a download in the browser), checked by loading it back.
    /// A file already at the path is never replaced: the scene goes under the first free
    /// numbered name beside it (`name-2.ron`, ...), which [`Editor::just_saved`] holds.
    Save(PathBuf),
    /// A question of the exercise: added (`index` None) or rewritten in place. With `compute`,
    /// its expected answer is the analysis layer's value from a run of the scene (refused where
    /// the quantity has no analysis: the engine checked against itself proves nothing).
    Ask {
        index: Option<usize>,
        question: Box<QuestionDef>,
        compute: bool,
    },
    /// Runs the scene headless for this question alone, at the level's own settings as
    /// `rigidlab check` runs it (not the solver panel's), and keeps the engine's and the
    /// analysis's values in [`Editor::preview`], for the teacher to see before saving.
    Preview(Box<QuestionDef>),
}

/// The longest run the window makes in a frame to preview a question, s (estimated by
/// `runner::budget`): a longer one is left to `rigidlab check`.
pub const PREVIEW_BUDGET_S: f64 = 2.0;

/// The engine's and the analysis's values of one question, read from a headless run of `scene`
/// with that question alone (its checks and other questions left out), as `rigidlab check` would
/// read it. Refused, with why, when the run would take longer than [`PREVIEW_BUDGET_S`] or stops.
pub fn preview_question(
    scene: &Scene,
    options: &Options,
    question: &QuestionDef,
) -> Result<QuestionResult, String> {
    let mut level = scene.level.clone();
    level.checks.clear();
    level.questions = vec![question.clone()];
    // The question as the validator would take it (a body it names that is not there, a
    // quantity that does not fit the level), before any run.
    let scene = editor::validated(scene, level)?;
    let estimate = Estimate::of(&scene.level, options, Mode::Check, None);
    if estimate.seconds > PREVIEW_BUDGET_S {
        return Err(format!(
            "the run would take about {:.0} s, too long to preview here: save and run `rigidlab check`",
            estimate.seconds
        ));
    }
    let report = runner::run_graded(&scene, options, &Default::default(), |_| {})
        .map_err(|e| e.to_string())?;
    report
        .questions
        .into_iter()
        .next()
        .ok_or_else(|| "the run read no question".to_string())
}

/// The edit history of the scene on screen and the last edit's note (shown in the panel).
#[derive(Resource, Debug, Default)]
pub struct Editor {
    pub history: History,
    /// What the last command did, and whether it worked.
    pub note: Option<(String, bool)>,
    /// The level the history belongs to (`Run::view_generation`: a newly opened level
    /// starts a new history).
    level_generation: u64,
    /// The file just saved (the level browser rescans): the path asked for, or the numbered
    /// name it went under where that was taken.
    pub just_saved: Option<PathBuf>,
    /// The scene as last opened or saved, and the level it belongs to (`view_generation`):
    /// the edits since are unsaved work (app/unsaved.rs asks before they are thrown away).
    saved: Option<(u64, crate::level::Level)>,
    /// A new scene was sent to the run: the next level on screen is its, with this history and
    /// nothing to lose yet.
    adopt_next: bool,
    /// The last question previewed (or computed) and its values, or why it could not be.
    pub preview: Option<(QuestionDef, Result<QuestionResult, String>)>,
}

impl Editor {
    /// The scene on screen has edits not saved since it was opened (undone edits do not count).
    pub fn unsaved(&self, phys: &Run) -> bool {
        matches!(&self.saved, Some((g, level)) if *g == phys.view_generation && *level != phys.scene.level)
    }

    /// The scene on screen counts as saved (it was just written).
    pub fn mark_saved(&mut self, phys: &Run) {
        self.mark_saved_level(phys.view_generation, &phys.scene.level);
    }

    /// `level` of the level on screen `view_generation` counts as saved.
    fn mark_saved_level(&mut self, view_generation: u64, level: &crate::level::Level) {
        self.saved = Some((view_generation, level.clone()));
    }
}

/// Registers the commands and applies them before the physics step of the frame: an edited scene
/// goes to the run as a [`PhysicsCommand::Edited`], applied in the same frame.
pub struct EditorPlugin;

impl Plugin for EditorPlugin {
    fn build(&self, app: &mut App) {
        app.add_message::<EditorCommand>()
            .init_resource::<Editor>()
            .add_systems(Update, run_commands.before(super::physics::PhysicsStep));
    }
}

fn run_commands(
    mut commands: MessageReader<EditorCommand>,
    mut ed: ResMut<Editor>,
    run: Res<Run>,
    mut run_commands: MessageWriter<PhysicsCommand>,
) {
    if ed.level_generation != run.view_generation {
        if std::mem::take(&mut ed.adopt_next) {
            // The new scene this editor made: its history goes on, and it is nothing to lose.
            ed.level_generation = run.view_generation;
            ed.mark_saved(&run);
        } else {
            // A newly opened level starts a new history, at once: its undo button must not
            // offer the last level's edits, nor its panel show their note.
            ed.history.clear();
            ed.note = None;
            ed.preview = None;
            ed.level_generation = run.view_generation;
        }
    }
    // The scene as this frame's commands left it (the run takes it after them).
    let mut edited: Option<(Scene, bool)> = None;
    for c in commands.read() {
        let phys: &Scene = edited.as_ref().map_or(&run.scene, |(s, _)| s);
        if ed
            .saved
            .as_ref()
            .is_none_or(|(g, _)| *g != run.view_generation)
        {
            // The level as opened, before its first edit.
            ed.mark_saved(&run);
        }
        let next: Result<(Scene, String), String> = match c {
            EditorCommand::Apply(e) => ed.history.apply(phys, e),
            EditorCommand::Undo => ed
                .history
                .undo(phys)
                .map(|s| (s, "undone".to_string()))
                .ok_or_else(|| "nothing to undo".to_string()),
            EditorCommand::Redo => ed
                .history
                .redo(phys)
                .map(|s| (s, "redone".to_string()))
                .ok_or_else(|| "nothing to redo".to_string()),
            EditorCommand::New => {
                let fresh = editor::empty_scene(PathBuf::from("my-scene.ron"));
                ed.history
                    .apply(phys, &Edit::Replace(Box::new(fresh.level.clone())))
                    .map(|(s, _)| {
                        // Saved under its own name, not the level it replaced.
                        let s = Scene {
                            file: fresh.file.clone(),
                            ..s
                        };
                        (
                            s,
                            "a new scene: a ground line; add bodies with the tools".into(),
                        )
                    })
            }
            EditorCommand::Preview(q) => {
                let r = preview_question(phys, &Options::default(), q);
                ed.note = Some(match &r {
                    Ok(r) => (preview_note(r), true),
                    Err(e) => (e.clone(), false),
                });
                ed.preview = Some(((**q).clone(), r));
                continue;
            }
            EditorCommand::Ask {
                index,
                question,
                compute,
            } => {
                let mut q = (**question).clone();
                let computed = if *compute {
                    let r = preview_question(phys, &Options::default(), &q);
                    ed.preview = Some((q.clone(), r.clone()));
                    match r {
                        Ok(QuestionResult {
                            analysis: Some(a), ..
                        }) if a.is_finite() => {
                            q.expected = a;
                            Ok(())
                        }
                        Ok(r) => Err(format!(
                            "not applied: {} has no analysis value to compute the answer from{}; type the textbook's answer",
                            q.id,
                            if r.note.is_empty() {
                                String::new()
                            } else {
                                format!(" ({})", r.note)
                            }
                        )),
                        Err(e) => Err(format!("not applied: {e}")),
                    }
                } else {
                    Ok(())
                };
                computed.and_then(|()| {
                    let e = match index {
                        None => Edit::AddQuestion(Box::new(q)),
                        Some(i) => Edit::ReplaceQuestion {
                            index: *i,
                            question: Box::new(q),
                        },
                    };
                    ed.history.apply(phys, &e)
                })
            }
            EditorCommand::Save(path) => {
                ed.note = Some(
                    // A file already there is kept: the scene goes under a numbered name.
                    match super::user_files::save_level_as(phys, path) {
                        Ok((used, m)) => {
                            ed.just_saved = Some(used);
                            let level = phys.level.clone();
                            ed.mark_saved_level(run.view_generation, &level);
                            (m, true)
                        }
                        Err(e) => (e, false),
                    },
                );
                continue;
            }
        };
        match next {
            Ok((scene, note)) => {
                // A new scene is fitted (the old view may not even show its ground) and is
                // nothing to lose yet; an edit keeps the user's view.
                let new = *c == EditorCommand::New;
                ed.adopt_next |= new;
                let refit = new || edited.as_ref().is_some_and(|(_, r)| *r);
                edited = Some((scene, refit));
                ed.note = Some((note, true));
            }
            Err(why) => ed.note = Some((why, false)),
        }
    }
    if let Some((scene, refit)) = edited {
        // The scene as it starts: the run starts over from it, paused.
        run_commands.write(PhysicsCommand::Edited {
            scene: Box::new(scene),
            refit,
        });
    }
}

/// A preview in one line: the engine's value, the analysis's, and when it was read. Where the
/// analysis has no value, one reason is given: the note's when it says why (an analysis whose
/// assumptions the scene breaks is "not applicable", which "no analysis formula" contradicted
/// on the same line), else that there is no formula for the quantity.
pub fn preview_note(r: &QuestionResult) -> String {
    let explained = r.note.contains("not applicable");
    let analysis = match r.analysis {
        Some(a) => format!(", analysis {a:.6} {}", r.unit),
        None if explained => String::new(),
        None => ", no analysis formula for it".into(),
    };
    let mut s = format!(
        "{}: engine {:.6} {}{analysis}, read at t = {:.4} s",
        r.id, r.engine, r.unit, r.time
    );
    if !r.note.is_empty() {
        s.push_str(&format!(" ({})", r.note));
    }
    s
}

/// A length for new things at the scale of the scene on screen: `fraction` of its size, rounded
/// to 1, 2 or 5 times a power of ten (a 0.2 m box, not 0.1873 m).
pub fn nice_length(scene_size: f64, fraction: f64) -> f64 {
    let x = (scene_size * fraction).max(1e-3);
    let p = 10f64.powf(x.log10().floor());
    let m = x / p;
    let n = if m < 1.5 {
        1.0
    } else if m < 3.5 {
        2.0
    } else if m < 7.5 {
        5.0
    } else {
        10.0
    };
    n * p
}

/// What the place tool puts where the user clicks.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Placeable {
    Box,
    Disc,
    Bar,
    Ground,
    Wall,
    /// A fixed 30 degree incline.
    Incline,
    /// A fixed half-circle bowl (an arc track ridden on its inside), its bottom at the click.
    Arc,
}

impl Placeable {
    pub const ALL: [Placeable; 7] = [
        Placeable::Box,
        Placeable::Disc,
        Placeable::Bar,
        Placeable::Ground,
        Placeable::Wall,
        Placeable::Incline,
        Placeable::Arc,
    ];

    pub fn name(self) -> &'static str {
        match self {
            Placeable::Box => "box",
            Placeable::Disc => "disc",
            Placeable::Bar => "bar",
            Placeable::Ground => "ground",
            Placeable::Wall => "wall",
            Placeable::Incline => "incline",
            Placeable::Arc => "arc",
        }
    }

    /// The edit that places it at `p`, sized for a scene `size` m across; bodies are 1 kg (a
    /// round mass, whatever their size: the sandbox used to fill them at 1000 kg/m^2).
    pub fn edit_at(self, p: DVec2, size: f64) -> Edit {
        let at = round_point(p, size);
        let at = (at.x, at.y);
        match self {
            Placeable::Box => Edit::AddBody {
                shape: NewShape::Box {
                    width: nice_length(size, 0.08),
                    height: nice_length(size, 0.05),
                },
                at,
                mass: 1.0,
            },
            Placeable::Disc => Edit::AddBody {
                shape: NewShape::Disc {
                    radius: nice_length(size, 0.04),
                },
                at,
                mass: 1.0,
            },
            Placeable::Bar => Edit::AddBody {
                shape: NewShape::Bar {
                    length: nice_length(size, 0.3),
                    thickness: nice_length(size, 0.015),
                },
                at,
                mass: 1.0,
            },
            Placeable::Ground => Edit::AddGround {
                y: at.1,
                width: nice_length(size, 3.0),
            },
            Placeable::Wall => Edit::AddWall {
                x: at.0,
                height: nice_length(size, 1.0),
            },
            Placeable::Incline => Edit::AddIncline {
                at,
                angle: 30f64.to_radians(),
                length: nice_length(size, 0.5),
            },
            Placeable::Arc => {
                let radius = nice_length(size, 0.25);
                Edit::AddArc {
                    center: (at.0, at.1 + radius),
                    radius,
                    start: std::f64::consts::PI,
                    end: std::f64::consts::TAU,
                    side: crate::level::ArcSide::Inside,
                }
            }
        }
    }
}

/// A clicked point rounded like [`Placeable::edit_at`] rounds it.
pub fn round_point(p: DVec2, size: f64) -> DVec2 {
    DVec2::new(round_to(p.x, size), round_to(p.y, size))
}

/// Rounds a clicked coordinate to a step of a thousandth of the scene (1 mm in a 1 m scene), so
/// a level file reads 0.25 and not 0.2487193.
fn round_to(x: f64, size: f64) -> f64 {
    let step = nice_length(size, 1e-3);
    (x / step).round() * step
}

/// What the join tool makes.
pub fn joint_name(kind: JointKind) -> &'static str {
    match kind {
        JointKind::Revolute => "pin",
        JointKind::Prismatic => "slider",
        JointKind::Fixed => "weld",
        JointKind::PinSlot => "pin in slot",
    }
}
