//! The energy and momentum panel: the current kinetic, potential and total energy and H about
//! the world origin, and their small line plots against time.

use super::super::color32;
use super::super::physics::{Physics, SeriesPoint};
use super::super::view::palette;
use super::{fmt, rich};
use bevy::prelude::*;
use bevy_egui::egui;

/// Draws the panel from the run's energy and momentum series.
pub(super) fn plots(ui: &mut egui::Ui, phys: &Physics) {
    ui.heading("Energy and momentum");
    let series = &phys.series;
    if let Some(p) = series.last() {
        egui::Grid::new("energies").num_columns(2).show(ui, |ui| {
            ui.label(rich("kinetic T", palette::VELOCITY));
            ui.label(format!("{:.5} J", p.kinetic));
            ui.end_row();
            ui.label(rich("potential V (gravity + springs)", palette::GRAVITY));
            ui.label(format!("{:.5} J", p.gravity + p.elastic));
            ui.end_row();
            ui.label(rich("total E = T + V", palette::TEXT));
            ui.label(format!("{:.5} J", p.total()));
            ui.end_row();
            ui.label(rich("H about the world origin", palette::MOMENTUM));
            ui.label(format!("{:.5} N m s", p.h_o));
            ui.end_row();
        });
    }
    line_plot(
        ui,
        series,
        &[
            (&|p: &SeriesPoint| p.kinetic, palette::VELOCITY),
            (&|p: &SeriesPoint| p.gravity + p.elastic, palette::GRAVITY),
            (&|p: &SeriesPoint| p.total(), palette::TEXT),
        ],
        "J",
    );
    line_plot(
        ui,
        series,
        &[(&|p: &SeriesPoint| p.h_o, palette::MOMENTUM)],
        "N m s",
    );
}

type Pick<'a> = &'a dyn Fn(&SeriesPoint) -> f64;

/// A small line plot against time, with the value range and time range written on it.
fn line_plot(ui: &mut egui::Ui, series: &[SeriesPoint], lines: &[(Pick, Color)], unit: &str) {
    let width = ui.available_width().min(320.0);
    let (rect, _) = ui.allocate_exact_size(egui::vec2(width, 110.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, egui::Color32::from_gray(250));
    painter.rect_stroke(
        rect,
        2.0,
        egui::Stroke::new(1.0, egui::Color32::from_gray(180)),
        egui::StrokeKind::Inside,
    );
    if series.len() < 2 {
        return;
    }
    let (t0, t1) = (
        series[0].t,
        series[series.len() - 1].t.max(series[0].t + 1e-9),
    );
    let mut lo = f64::INFINITY;
    let mut hi = f64::NEG_INFINITY;
    for (f, _) in lines {
        for p in series {
            let v = f(p);
            if v.is_finite() {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
    }
    if !(lo <= hi) {
        return;
    }
    let pad = ((hi - lo) * 0.08).max(1e-9 * hi.abs().max(1.0));
    let (lo, hi) = (lo - pad, hi + pad);
    let inner = rect.shrink2(egui::vec2(4.0, 14.0));
    let map = |t: f64, v: f64| {
        egui::pos2(
            inner.min.x + ((t - t0) / (t1 - t0)) as f32 * inner.width(),
            inner.max.y - ((v - lo) / (hi - lo)) as f32 * inner.height(),
        )
    };
    if lo < 0.0 && hi > 0.0 {
        painter.line_segment(
            [map(t0, 0.0), map(t1, 0.0)],
            egui::Stroke::new(1.0, egui::Color32::from_gray(200)),
        );
    }
    let stride = (series.len() / (2 * width as usize).max(1)).max(1);
    for (f, c) in lines {
        let pts: Vec<egui::Pos2> = series
            .iter()
            .step_by(stride)
            .map(|p| map(p.t, f(p)))
            .collect();
        painter.add(egui::Shape::line(pts, egui::Stroke::new(1.5, color32(*c))));
    }
    let font = egui::FontId::proportional(10.0);
    let gray = egui::Color32::from_gray(90);
    painter.text(
        rect.left_top() + egui::vec2(3.0, 1.0),
        egui::Align2::LEFT_TOP,
        format!("{} {unit}", fmt(hi)),
        font.clone(),
        gray,
    );
    painter.text(
        rect.left_bottom() + egui::vec2(3.0, -1.0),
        egui::Align2::LEFT_BOTTOM,
        format!("{} {unit}", fmt(lo)),
        font.clone(),
        gray,
    );
    painter.text(
        rect.right_bottom() + egui::vec2(-3.0, -1.0),
        egui::Align2::RIGHT_BOTTOM,
        format!("t = {:.2} s", t1),
        font,
        gray,
    );
}
