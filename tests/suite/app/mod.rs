//! The Bevy sandbox (src/app), headless: the window, editor, inspector, playback and the web page.

mod assignment_list;
mod blows;
mod course_progress;
mod editor_commands;
mod editor_core;
mod exercise_questions;
mod help_tour;
mod hints;
mod inspector_fields;
mod key_chords;
mod kinetic_copy;
mod label_placement;
mod measure;
mod mouse_tools;
mod names_overlay;
mod own_numbers;
mod playback;
mod plot_labels;
mod plugins;
mod predict_first;
mod student_window;
mod unsaved_work;
mod web_page;
mod window;
mod window_advice;
mod window_diagram;
