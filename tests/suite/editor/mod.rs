//! The editor's core (src/editor): placing bodies and curved tracks; the window's editor is in
//! app/.

mod curved_tracks;
mod placement;
