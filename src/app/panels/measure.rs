//! The measuring panel: a stopwatch on simulated time, a period timer for the selected body (the
//! same zero-crossing reading the period questions use, analysis::oscillation), the clicked point's
//! position, velocity and acceleration (RK-6, RK-10), and the ruler's and protractor's last
//! measurements.

use super::super::run::Run;
use super::super::tools::{Tool, ToolState};
use super::super::ui::rich;
use super::super::view::palette;
use crate::analysis::kinematics::{body_point_velocity, point_acceleration};
use crate::analysis::oscillation::Crossings;
use bevy_egui::egui;
use glam::DVec2;

/// A stopwatch reading the simulation's clock (not the wall clock: time scale and pauses do not
/// change what it measures).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Stopwatch {
    pub start: Option<f64>,
    pub stop: Option<f64>,
    pub laps: Vec<f64>,
}

impl Stopwatch {
    /// Elapsed simulated time at `now`, s.
    pub fn elapsed(&self, now: f64) -> Option<f64> {
        self.start.map(|s| self.stop.unwrap_or(now) - s)
    }
}

/// The period of the selected body's swing or oscillation from its recorded omega (or, for a
/// body that does not turn, its velocity along its largest motion), and how many periods it spans.
pub fn period_of(phys: &Run, i: usize) -> Option<(f64, usize)> {
    let samples = phys.body_series.get(i)?;
    let turning = samples.iter().any(|p| p.omega.abs() > 1e-6);
    let mut c = Crossings::default();
    if turning {
        for p in samples {
            c.add(p.t, p.omega);
        }
    } else {
        // A body on a spring: the velocity component along the direction it moves most.
        let (sx, sy) = samples.iter().fold((0.0, 0.0), |(a, b), p| {
            (a + p.v.x * p.v.x, b + p.v.y * p.v.y)
        });
        for p in samples {
            c.add(p.t, if sx >= sy { p.v.x } else { p.v.y });
        }
    }
    let t = c.period();
    (t.is_finite() && c.periods() > 0).then(|| (t, c.periods()))
}

pub(super) fn measure(
    ui: &mut egui::Ui,
    phys: &Run,
    tools: &mut ToolState,
    watch: &mut Stopwatch,
    selected: Option<usize>,
    point: Option<(usize, DVec2)>,
) {
    ui.heading("Measure");
    let now = phys.snapshot().time;
    ui.horizontal(|ui| {
        ui.label("stopwatch");
        let running = watch.start.is_some() && watch.stop.is_none();
        if !running && ui.button("start").clicked() {
            *watch = Stopwatch {
                start: Some(now),
                ..Default::default()
            };
        }
        if running && ui.button("lap").clicked() {
            watch.laps.push(now - watch.start.unwrap_or(now));
        }
        if running && ui.button("stop").clicked() {
            watch.stop = Some(now);
        }
        if watch.start.is_some() && ui.button("clear").clicked() {
            *watch = Stopwatch::default();
        }
        if let Some(e) = watch.elapsed(now) {
            ui.monospace(format!("{e:.4} s"));
        }
    });
    if !watch.laps.is_empty() {
        let laps: Vec<String> = watch.laps.iter().map(|l| format!("{l:.4}")).collect();
        ui.label(rich(format!("laps: {} s", laps.join(", ")), palette::OUTLINE).small());
    }
    if let Some(i) = selected {
        let name = phys
            .scene
            .level
            .bodies
            .get(i)
            .map_or("", |b| b.name.as_str());
        match period_of(phys, i) {
            Some((t, n)) => ui.label(format!(
                "period of {name}: {t:.4} s (mean of {n} periods, between ω's zero crossings)"
            )),
            None => ui.label(
                rich(
                    format!("period of {name}: play until it has swung back twice"),
                    palette::OUTLINE,
                )
                .small(),
            ),
        };
    }
    if let Some((i, local)) = point {
        point_readout(ui, phys, i, local);
    }
    ui.horizontal(|ui| {
        ui.selectable_value(&mut tools.tool, Tool::Protractor, "protractor");
        match tools.protractor.and_then(|p| p.angle()) {
            Some(a) => ui.label(format!("{:.2}° between the arms", a.to_degrees())),
            // Wrapped: beside a button a label does not wrap, and this one, at a legible size,
            // widened the whole panel.
            None => ui.add(
                egui::Label::new(
                    rich(
                        "drag from the vertex along one arm, then click the other arm's end",
                        palette::OUTLINE,
                    )
                    .small(),
                )
                .wrap(),
            ),
        };
    });
    ui.horizontal(|ui| {
        ui.selectable_value(&mut tools.tool, Tool::Ruler, "ruler");
        match tools.ruler {
            Some((a, b)) => {
                let d = b - a;
                ui.label(format!(
                    "{:.4} m at {:.1}° (Δx {:.4}, Δy {:.4})",
                    d.length(),
                    d.y.atan2(d.x).to_degrees(),
                    d.x,
                    d.y
                ));
            }
            None => {
                ui.add(
                    egui::Label::new(
                        rich(
                            "drag in the scene to measure a length and its angle",
                            palette::OUTLINE,
                        )
                        .small(),
                    )
                    .wrap(),
                );
            }
        }
    });
}

/// The clicked point P of body `i` (select tool): where it is, v_P = v_G + omega k x r_P/G
/// (RK-6) and a_P = a_G + alpha k x r_P/G - omega^2 r_P/G (RK-10), with a_G and alpha over the
/// last physics step (as the acceleration overlay draws them).
fn point_readout(ui: &mut egui::Ui, phys: &Run, i: usize, local: DVec2) {
    let s = phys.snapshot();
    let Some(b) = s.bodies.get(i) else {
        return;
    };
    let p = b.world_point(local);
    let v = body_point_velocity(b, p);
    let name = phys
        .scene
        .level
        .bodies
        .get(i)
        .map_or("", |d| d.name.as_str());
    ui.label(format!("point P on {name}: ({:.4}, {:.4}) m", p.x, p.y));
    ui.monospace(format!(
        "v_P = ({:+.4}, {:+.4}) m/s, |v_P| {:.4}",
        v.x,
        v.y,
        v.length()
    ));
    let acc = phys
        .prev_velocities
        .as_ref()
        .map(|(prev, dt)| super::super::quantities::accelerations(s, prev, *dt));
    if let Some((a_g, alpha)) = acc.and_then(|a| a.get(i).copied()) {
        let a = point_acceleration(a_g, alpha, b.omega, p - b.com);
        ui.monospace(format!(
            "a_P = ({:+.4}, {:+.4}) m/s², |a_P| {:.4}",
            a.x,
            a.y,
            a.length()
        ));
    }
}
