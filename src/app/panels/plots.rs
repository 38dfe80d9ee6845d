//! The plots panel: the current kinetic, potential and total energy and H about the chosen O
//! with their line plots against time, and a plot of the selected body's quantity of choice
//! (theta, omega, x_G, y_G, |v_G|, the joints' reaction |R|), each with a cursor readout and a
//! CSV export.

use super::super::run::{BodySample, Run, SeriesPoint};
use super::super::ui::color32;
use super::super::ui::{fmt, rich};
use super::super::view::palette;
use bevy::prelude::*;
use bevy_egui::egui;

/// A quantity of a body to plot against time.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum BodyPlot {
    Angle,
    #[default]
    Omega,
    X,
    Y,
    Speed,
    Reaction,
}

impl BodyPlot {
    const ALL: [BodyPlot; 6] = [
        BodyPlot::Angle,
        BodyPlot::Omega,
        BodyPlot::X,
        BodyPlot::Y,
        BodyPlot::Speed,
        BodyPlot::Reaction,
    ];

    fn label(self) -> &'static str {
        match self {
            BodyPlot::Angle => "θ, rad",
            BodyPlot::Omega => "ω, rad/s",
            BodyPlot::X => "x_G, m",
            BodyPlot::Y => "y_G, m",
            BodyPlot::Speed => "|v_G|, m/s",
            BodyPlot::Reaction => "joints' reaction |R|, N",
        }
    }

    fn unit(self) -> &'static str {
        match self {
            BodyPlot::Angle => "rad",
            BodyPlot::Omega => "rad/s",
            BodyPlot::X | BodyPlot::Y => "m",
            BodyPlot::Speed => "m/s",
            BodyPlot::Reaction => "N",
        }
    }

    fn of(self, p: &BodySample) -> f64 {
        match self {
            BodyPlot::Angle => p.angle,
            BodyPlot::Omega => p.omega,
            BodyPlot::X => p.g.x,
            BodyPlot::Y => p.g.y,
            BodyPlot::Speed => p.v.length(),
            BodyPlot::Reaction => p.reaction.length(),
        }
    }
}

/// A body's samples as CSV: one row per sample, SI units, a header naming each column.
pub fn body_csv(samples: &[BodySample]) -> String {
    let mut out = String::from("t_s,x_G_m,y_G_m,theta_rad,omega_rad_s,vx_m_s,vy_m_s,Rx_N,Ry_N\n");
    for p in samples {
        out += &format!(
            "{},{},{},{},{},{},{},{},{}\n",
            p.t, p.g.x, p.g.y, p.angle, p.omega, p.v.x, p.v.y, p.reaction.x, p.reaction.y
        );
    }
    out
}

/// The energy series as CSV.
pub fn energy_csv(series: &[SeriesPoint]) -> String {
    let mut out = String::from("t_s,T_J,V_gravity_J,V_elastic_J,E_J,H_origin_Nms,Gx_Ns,Gy_Ns\n");
    for p in series {
        out += &format!(
            "{},{},{},{},{},{},{},{}\n",
            p.t,
            p.kinetic,
            p.gravity,
            p.elastic,
            p.total(),
            p.h_o,
            p.momentum.x,
            p.momentum.y
        );
    }
    out
}

/// The selected body's plot: a choice of quantity, against time or another quantity (a phase
/// plot: omega against theta), and its CSV.
pub(super) fn body_plot(
    ui: &mut egui::Ui,
    phys: &Run,
    selected: Option<usize>,
    (choice, against): (&mut BodyPlot, &mut Option<BodyPlot>),
    message: &mut Option<(String, bool)>,
) {
    let Some(i) = selected else {
        ui.label(
            rich(
                "select a body to plot its θ, ω, x, y, v or R against time",
                palette::OUTLINE,
            )
            .small(),
        );
        return;
    };
    let Some(samples) = phys.body_series.get(i).filter(|s| !s.is_empty()) else {
        ui.label(rich("a fixed body: nothing to plot", palette::OUTLINE).small());
        return;
    };
    let name = phys
        .scene
        .level
        .bodies
        .get(i)
        .map_or("body", |b| b.name.as_str());
    ui.horizontal(|ui| {
        ui.label(egui::RichText::new(name).strong());
        egui::ComboBox::from_id_salt("body-plot")
            .selected_text(choice.label())
            .show_ui(ui, |ui| {
                for q in BodyPlot::ALL {
                    ui.selectable_value(choice, q, q.label());
                }
            });
        ui.label("against");
        egui::ComboBox::from_id_salt("body-plot-x")
            .selected_text(against.map_or("t, s", |q| q.label()))
            .show_ui(ui, |ui| {
                ui.selectable_value(against, None, "t, s");
                for q in BodyPlot::ALL {
                    ui.selectable_value(against, Some(q), q.label());
                }
            });
    });
    if let Some(x) = *against {
        xy_plot(ui, samples, x, *choice);
        body_export(ui, phys, name, samples, message);
        return;
    }
    let q = *choice;
    let points: Vec<SeriesPoint> = samples
        .iter()
        .map(|p| SeriesPoint {
            t: p.t,
            kinetic: q.of(p),
            gravity: 0.0,
            elastic: 0.0,
            h_o: 0.0,
            momentum: glam::DVec2::ZERO,
        })
        .collect();
    line_plot(
        ui,
        &points,
        &[(&|p: &SeriesPoint| p.kinetic, palette::VELOCITY)],
        q.unit(),
    );
    if samples[0].t > 0.0 {
        ui.label(
            rich(
                format!(
                    "recorded from t = {:.3} s, when it was selected",
                    samples[0].t
                ),
                palette::OUTLINE,
            )
            .small(),
        );
    }
    body_export(ui, phys, name, samples, message);
}

/// The selected body's CSV export button (every body plot has one).
fn body_export(
    ui: &mut egui::Ui,
    phys: &Run,
    name: &str,
    samples: &[BodySample],
    message: &mut Option<(String, bool)>,
) {
    if ui
        .button("export CSV")
        .on_hover_text(
            "t, x_G, y_G, θ, ω, v_G, R of this body, SI units (a file already there is kept)",
        )
        .clicked()
    {
        let stem = phys
            .scene
            .file
            .file_stem()
            .map_or("scene".into(), |s| s.to_string_lossy().to_string());
        let path = export_path(&format!("{stem}-{name}.csv"));
        *message = Some(
            match super::super::user_files::deliver(&path, body_csv(samples).as_bytes(), "text/csv")
            {
                Ok(m) => (m, true),
                Err(e) => (e, false),
            },
        );
    }
}

/// The smallest and largest finite values, if any: what a plot's labels print.
pub fn extremes(values: impl IntoIterator<Item = f64>) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .into_iter()
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), v| {
            (l.min(v), h.max(v))
        });
    (lo <= hi).then_some((lo, hi))
}

/// The range a plot draws over: the extremes with a margin of 8% each side (the line never
/// touches the frame). Only the drawing uses it; the labels print the extremes themselves.
pub fn drawn_range((lo, hi): (f64, f64)) -> (f64, f64) {
    let pad = ((hi - lo) * 0.08).max(1e-9 * hi.abs().max(1.0));
    (lo - pad, hi + pad)
}

/// The ticks of an axis over `lo..=hi`: multiples of a step of 1, 2 or 5 times a power of ten,
/// at most `most` of them (and at least 2 when the range is not empty), each the step times an
/// integer so 0 is printed 0 and not 1e-17.
pub fn nice_ticks(lo: f64, hi: f64, most: usize) -> Vec<f64> {
    if !(lo.is_finite() && hi.is_finite()) || hi <= lo || most < 2 {
        return Vec::new();
    }
    let rough = (hi - lo) / (most - 1) as f64;
    let p = 10f64.powf(rough.log10().floor());
    let step = [1.0, 2.0, 5.0, 10.0]
        .iter()
        .map(|m| m * p)
        .find(|s| (((hi / s).floor() - (lo / s).ceil()) as usize) < most)
        .unwrap_or(10.0 * p);
    let (first, last) = ((lo / step).ceil() as i64, (hi / step).floor() as i64);
    (first..=last).map(|k| k as f64 * step).collect()
}

/// Grid lines and tick labels on a plot's frame: the value axis on the left of `inner`, the
/// other along its bottom (egui draws no axes by itself: the plots had none).
fn axes(
    painter: &egui::Painter,
    inner: egui::Rect,
    (x0, x1): (f64, f64),
    (y0, y1): (f64, f64),
    font: &egui::FontId,
) {
    let grid = egui::Stroke::new(1.0, egui::Color32::from_gray(225));
    let ink = egui::Color32::from_gray(70);
    for v in nice_ticks(y0, y1, 5) {
        let y = inner.max.y - ((v - y0) / (y1 - y0)) as f32 * inner.height();
        painter.line_segment(
            [egui::pos2(inner.min.x, y), egui::pos2(inner.max.x, y)],
            grid,
        );
        painter.text(
            egui::pos2(inner.min.x - 3.0, y),
            egui::Align2::RIGHT_CENTER,
            fmt(v),
            font.clone(),
            ink,
        );
    }
    for v in nice_ticks(x0, x1, 6) {
        let x = inner.min.x + ((v - x0) / (x1 - x0)) as f32 * inner.width();
        painter.line_segment(
            [egui::pos2(x, inner.min.y), egui::pos2(x, inner.max.y)],
            grid,
        );
        painter.text(
            egui::pos2(x, inner.max.y + 1.0),
            egui::Align2::CENTER_TOP,
            fmt(v),
            font.clone(),
            ink,
        );
    }
}

/// Room around a plot's lines: the value ticks on the left, the range on top, the other
/// axis's ticks and name at the bottom.
fn plot_area(rect: egui::Rect, bottom: f32) -> egui::Rect {
    egui::Rect::from_min_max(
        rect.min + egui::vec2(40.0, 16.0),
        rect.max - egui::vec2(8.0, bottom),
    )
}

/// The labels of a plot's value axis: the largest value at the top, the smallest at the bottom.
pub fn extreme_labels((lo, hi): (f64, f64), unit: &str) -> (String, String) {
    (
        format!("max {} {unit}", fmt(hi)),
        format!("min {} {unit}", fmt(lo)),
    )
}

/// The sample of a phase plot nearest the pointer, in screen distance; `map` is the plot's
/// mapping from values to the screen.
pub fn nearest_sample(
    pts: &[(f64, f64)],
    map: impl Fn(f64, f64) -> egui::Pos2,
    pointer: egui::Pos2,
) -> Option<usize> {
    pts.iter()
        .enumerate()
        .map(|(k, &(a, b))| (k, map(a, b).distance_sq(pointer)))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map(|(k, _)| k)
}

/// One quantity against another over the run (a phase plot), with both ranges written on it
/// and a readout of the sample nearest the pointer.
fn xy_plot(ui: &mut egui::Ui, samples: &[BodySample], x: BodyPlot, y: BodyPlot) {
    let width = ui.available_width().min(320.0);
    let (rect, hover) = ui.allocate_exact_size(egui::vec2(width, 180.0), egui::Sense::hover());
    let painter = ui.painter_at(rect);
    painter.rect_filled(rect, 2.0, egui::Color32::from_gray(250));
    let pts: Vec<(f64, f64)> = samples
        .iter()
        .map(|p| (x.of(p), y.of(p)))
        .filter(|(a, b)| a.is_finite() && b.is_finite())
        .collect();
    let ts: Vec<f64> = samples
        .iter()
        .filter(|p| x.of(p).is_finite() && y.of(p).is_finite())
        .map(|p| p.t)
        .collect();
    if pts.len() < 2 {
        return;
    }
    let (Some(xr), Some(yr)) = (
        extremes(pts.iter().map(|p| p.0)),
        extremes(pts.iter().map(|p| p.1)),
    ) else {
        return;
    };
    let ((x0, x1), (y0, y1)) = (drawn_range(xr), drawn_range(yr));
    // Below the ticks, the other quantity's name and range.
    let inner = plot_area(rect, 30.0);
    let font = egui::FontId::proportional(super::super::ui::SMALL_TEXT);
    axes(&painter, inner, (x0, x1), (y0, y1), &font);
    let map = |a: f64, b: f64| {
        egui::pos2(
            inner.min.x + ((a - x0) / (x1 - x0)) as f32 * inner.width(),
            inner.max.y - ((b - y0) / (y1 - y0)) as f32 * inner.height(),
        )
    };
    let line: Vec<egui::Pos2> = pts.iter().map(|&(a, b)| map(a, b)).collect();
    painter.add(egui::Shape::line(
        line,
        egui::Stroke::new(1.5, color32(palette::VELOCITY)),
    ));
    let gray = egui::Color32::from_gray(90);
    painter.text(
        rect.left_top() + egui::vec2(3.0, 1.0),
        egui::Align2::LEFT_TOP,
        format!("{}: {} to {}", y.label(), fmt(yr.0), fmt(yr.1)),
        font.clone(),
        gray,
    );
    painter.text(
        rect.right_bottom() + egui::vec2(-3.0, -1.0),
        egui::Align2::RIGHT_BOTTOM,
        format!("{}: {} to {}", x.label(), fmt(xr.0), fmt(xr.1)),
        font.clone(),
        gray,
    );
    // The cursor readout: the sample nearest the pointer, marked, with its time and values.
    if let Some(k) = hover
        .hover_pos()
        .and_then(|pos| nearest_sample(&pts, map, pos))
    {
        let (a, b) = pts[k];
        let at = map(a, b);
        painter.circle_stroke(
            at,
            4.0,
            egui::Stroke::new(1.5, egui::Color32::from_gray(40)),
        );
        painter.text(
            inner.left_top() + egui::vec2(3.0, 1.0),
            egui::Align2::LEFT_TOP,
            format!(
                "t = {:.3} s: {} {}, {} {}",
                ts[k],
                fmt(a),
                x.unit(),
                fmt(b),
                y.unit()
            ),
            font,
            egui::Color32::from_gray(30),
        );
    }
}

/// Where an export goes: `exports/` of the working directory in the window, a download in the page.
fn export_path(name: &str) -> std::path::PathBuf {
    if cfg!(target_arch = "wasm32") {
        name.into()
    } else {
        std::path::Path::new("exports").join(name)
    }
}

/// Draws the panel from the run's energy and momentum series.
pub(super) fn plots(
    ui: &mut egui::Ui,
    phys: &Run,
    origin: glam::DVec2,
    message: &mut Option<(String, bool)>,
) {
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
            ui.label(rich(
                format!("H about O ({}, {}) m", fmt(origin.x), fmt(origin.y)),
                palette::MOMENTUM,
            ));
            ui.label(format!("{:.5} N m s", p.h_about(origin)));
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
        &[(&|p: &SeriesPoint| p.h_about(origin), palette::MOMENTUM)],
        "N m s",
    );
    if ui
        .button("export CSV")
        .on_hover_text("t, T, V, E and H_O of the run, SI units")
        .clicked()
    {
        let stem = phys
            .scene
            .file
            .file_stem()
            .map_or("scene".into(), |s| s.to_string_lossy().to_string());
        let path = export_path(&format!("{stem}-energy.csv"));
        *message = Some(
            match super::super::user_files::deliver(
                &path,
                energy_csv(series).as_bytes(),
                "text/csv",
            ) {
                Ok(m) => (m, true),
                Err(e) => (e, false),
            },
        );
    }
}

type Pick<'a> = &'a dyn Fn(&SeriesPoint) -> f64;

/// A small line plot against time, with the value range and time range written on it.
fn line_plot(ui: &mut egui::Ui, series: &[SeriesPoint], lines: &[(Pick, Color)], unit: &str) {
    let width = ui.available_width().min(320.0);
    let (rect, hover) = ui.allocate_exact_size(egui::vec2(width, 130.0), egui::Sense::hover());
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
    let Some(extent) = extremes(lines.iter().flat_map(|(f, _)| series.iter().map(f))) else {
        return;
    };
    let (lo, hi) = drawn_range(extent);
    let inner = plot_area(rect, 16.0);
    let font = egui::FontId::proportional(super::super::ui::SMALL_TEXT);
    axes(&painter, inner, (t0, t1), (lo, hi), &font);
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
    let gray = egui::Color32::from_gray(90);
    // The cursor readout: the sample nearest the pointer's time, each line's value there.
    if let Some(pos) = hover.hover_pos() {
        let t = t0 + ((pos.x - inner.min.x) / inner.width()).clamp(0.0, 1.0) as f64 * (t1 - t0);
        let k = series.partition_point(|p| p.t < t).min(series.len() - 1);
        let p = &series[k];
        painter.line_segment(
            [
                egui::pos2(map(p.t, lo).x, inner.min.y),
                egui::pos2(map(p.t, lo).x, inner.max.y),
            ],
            egui::Stroke::new(1.0, egui::Color32::from_gray(150)),
        );
        let values: Vec<String> = lines
            .iter()
            .map(|(f, _)| format!("{} {unit}", fmt(f(p))))
            .collect();
        painter.text(
            rect.right_top() + egui::vec2(-3.0, 1.0),
            egui::Align2::RIGHT_TOP,
            format!("t = {:.3} s: {}", p.t, values.join(", ")),
            font.clone(),
            egui::Color32::from_gray(30),
        );
    }
    // The labels print the extremes of the series, not the drawn range's margin; the readout
    // takes their place while the pointer is on the plot.
    if hover.hover_pos().is_none() {
        let (top, bottom) = extreme_labels(extent, unit);
        painter.text(
            rect.left_top() + egui::vec2(3.0, 1.0),
            egui::Align2::LEFT_TOP,
            format!("{top} · {bottom}"),
            font.clone(),
            gray,
        );
    }
    painter.text(
        rect.left_bottom() + egui::vec2(3.0, -1.0),
        egui::Align2::LEFT_BOTTOM,
        "t, s",
        font,
        gray,
    );
}
