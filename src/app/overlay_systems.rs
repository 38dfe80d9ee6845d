//! The overlays drawn in the window: one Bevy system per overlay, each run only while its switch
//! is on, in the drawing order of [`Overlay::ALL`] (the shape of avian's debug rendering). They
//! add to this frame's [`Drawing`] after the scene's lines and before the tools' marks
//! ([`DrawStep`]); `overlays::build` draws the same list in one call, for tests and tools.

use super::draw::{DrawStep, Drawing};
use super::overlays::{Overlay, Overlays, Scales};
use super::run::Run;
use super::view::Outlines;
use bevy::ecs::system::SystemParam;
use bevy::prelude::*;

/// One system per overlay, in [`DrawStep::Overlays`].
pub struct OverlaysPlugin;

impl Plugin for OverlaysPlugin {
    fn build(&self, app: &mut App) {
        app.init_resource::<Overlays>()
            .init_resource::<Scales>()
            .add_systems(
                Update,
                (
                    names.run_if(on(Overlay::Names)),
                    trails.run_if(on(Overlay::Trails)),
                    velocity.run_if(on(Overlay::Velocity)),
                    acceleration.run_if(on(Overlay::Acceleration)),
                    instant_centers.run_if(on(Overlay::InstantCenters)),
                    centers_of_percussion.run_if(on(Overlay::CentersOfPercussion)),
                    diagrams.run_if(on(Overlay::Diagrams)),
                    blows.run_if(on(Overlay::Blows)),
                    momentum.run_if(on(Overlay::Momentum)),
                )
                    .chain()
                    .in_set(DrawStep::Overlays),
            );
    }
}

/// The run condition of overlay `o`: its switch is on.
fn on(o: Overlay) -> impl FnMut(Res<Overlays>) -> bool + Clone {
    move |ov: Res<Overlays>| o.is_on(&ov)
}

/// What every overlay reads (the switches, the run, the bodies' outlines, this frame's scales)
/// and the drawing it adds to.
#[derive(SystemParam)]
struct OverlayInput<'w> {
    ov: Res<'w, Overlays>,
    run: Res<'w, Run>,
    outlines: Res<'w, Outlines>,
    scales: Res<'w, Scales>,
    drawing: ResMut<'w, Drawing>,
}

impl OverlayInput<'_> {
    fn draw(&mut self, o: Overlay) {
        o.draw(
            &self.ov,
            &self.run,
            &self.outlines.bodies,
            &self.scales,
            &mut self.drawing,
        );
    }
}

fn names(mut input: OverlayInput) {
    input.draw(Overlay::Names);
}

fn trails(mut input: OverlayInput) {
    input.draw(Overlay::Trails);
}

fn velocity(mut input: OverlayInput) {
    input.draw(Overlay::Velocity);
}

fn acceleration(mut input: OverlayInput) {
    input.draw(Overlay::Acceleration);
}

fn instant_centers(mut input: OverlayInput) {
    input.draw(Overlay::InstantCenters);
}

fn centers_of_percussion(mut input: OverlayInput) {
    input.draw(Overlay::CentersOfPercussion);
}

fn diagrams(mut input: OverlayInput) {
    input.draw(Overlay::Diagrams);
}

fn blows(mut input: OverlayInput) {
    input.draw(Overlay::Blows);
}

fn momentum(mut input: OverlayInput) {
    input.draw(Overlay::Momentum);
}
