//! Pareto plots: cost against error on log axes, a curve per knob, the front marked.

use plotters::element::IntoDynElement;
use plotters::prelude::*;
use std::path::Path;

/// The bundled font (pure Rust text rendering: no fontconfig).

/// plotters registers fonts only off the web (the studies are not built into the web page's
/// work, but the core they live in is).
#[cfg(target_arch = "wasm32")]
fn register_font() {}

#[cfg(not(target_arch = "wasm32"))]
fn register_font() {
    static FONT: &[u8] = include_bytes!("../../../assets/fonts/DejaVuSans.ttf");
    static ONCE: std::sync::Once = std::sync::Once::new();
    ONCE.call_once(|| {
        for style in [FontStyle::Normal, FontStyle::Bold] {
            // The bytes are a valid TrueType font shipped with the crate.
            let _ = plotters::style::register_font("sans-serif", style, FONT);
        }
    });
}

/// One knob's curve: (cost, error) points in sweep order.
pub struct Curve {
    pub label: String,
    pub color: RGBColor,
    pub points: Vec<(f64, f64)>,
    /// How its points are drawn (an engine each, when a plot has two).
    pub marker: Marker,
}

/// A point's marker: rapier's circles, Box2D's triangles.
#[derive(Clone, Copy, PartialEq, Eq)]
pub enum Marker {
    Circle,
    Triangle,
}

/// One engine's Pareto front (cost, error), sorted by cost.
pub struct Front {
    pub label: String,
    pub color: RGBColor,
    pub marker: Marker,
    pub points: Vec<(f64, f64)>,
}

/// One chart: an error measure against cost.
pub struct Panel {
    pub title: String,
    pub y_desc: String,
    pub curves: Vec<Curve>,
    /// The Pareto fronts, one per engine.
    pub fronts: Vec<Front>,
    /// Points meeting the level's tolerance (ringed).
    pub meets: Vec<(f64, f64)>,
    /// Labelled points (the level's settings, rapier's defaults).
    pub marks: Vec<(String, (f64, f64))>,
    /// Errors at or below this are drawn at it (exact results on a log axis).
    pub floor: f64,
}

/// The Pareto fronts' colours: rapier's black, Box2D's dark orange.
pub const FRONT_RAPIER: RGBColor = RGBColor(0, 0, 0);
pub const FRONT_BOX2D: RGBColor = RGBColor(200, 90, 0);

pub const COLORS: [RGBColor; 6] = [
    RGBColor(31, 119, 180),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
];

fn sci(v: &f64) -> String {
    if *v <= 0.0 {
        return "0".into();
    }
    let e = v.log10().floor();
    let m = v / 10f64.powf(e);
    // Label 1, 2 and 5 of each decade only: log axes get a tick per integer mantissa.
    let near = |x: f64| (m - x).abs() < 1e-3 * x;
    if near(1.0) || near(10.0) {
        format!("1e{}", if near(10.0) { e as i64 + 1 } else { e as i64 })
    } else if near(2.0) || near(5.0) {
        format!("{:.0}e{}", m, e as i64)
    } else {
        String::new()
    }
}

/// Draws the panels side by side into a PNG (or SVG when the path ends in .svg).
pub fn draw(path: &Path, caption: &str, panels: &[Panel]) -> Result<(), String> {
    register_font();
    let w = 640 * panels.len().max(1) as u32;
    let h = 560;
    let svg = path.extension().is_some_and(|e| e == "svg");
    // Drawn in memory, then written whole (crate::files): a plot that cannot be written is an
    // error the study reports, and an earlier plot stays as it was.
    let write = |bytes: &[u8]| {
        crate::files::write_over_own(path, bytes, plot_mark(svg))
            .map_err(|e| format!("{}: {e}", path.display()))
    };
    if svg {
        let mut text = String::new();
        {
            let root = SVGBackend::with_string(&mut text, (w, h)).into_drawing_area();
            draw_on(root, caption, panels)?;
        }
        write(format!("{}\n{text}", crate::files::TEXT_MARK).as_bytes())
    } else {
        let mut rgb = vec![0u8; (w * h * 3) as usize];
        {
            let root = BitMapBackend::with_buffer(&mut rgb, (w, h)).into_drawing_area();
            draw_on(root, caption, panels)?;
        }
        write(&palette_png(w, h, &rgb)?)
    }
}

/// How a plot shows that rigidlab wrote it: a PNG's text chunk, an SVG's first line.
pub fn plot_mark(svg: bool) -> crate::files::Mark<'static> {
    if svg {
        crate::files::Mark::FirstLine(crate::files::TEXT_MARK)
    } else {
        crate::files::Mark::Png
    }
}

/// Writes an RGB image as an 8-bit palette PNG: a plot has few colours (its anti-aliased edges
/// aside), so 256 chosen by NeuQuant look the same at a quarter of the RGB file's size.
fn palette_png(w: u32, h: u32, rgb: &[u8]) -> Result<Vec<u8>, String> {
    let rgba: Vec<u8> = rgb
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    let quant = color_quant::NeuQuant::new(10, 256, &rgba);
    let palette: Vec<u8> = quant
        .color_map_rgba()
        .chunks_exact(4)
        .flat_map(|c| [c[0], c[1], c[2]])
        .collect();
    let indices: Vec<u8> = rgba
        .chunks_exact(4)
        .map(|p| quant.index_of(p) as u8)
        .collect();
    let mut out = Vec::new();
    {
        let mut enc = png::Encoder::new(&mut out, w, h);
        enc.set_color(png::ColorType::Indexed);
        enc.set_depth(png::BitDepth::Eight);
        enc.set_palette(palette);
        enc.set_compression(png::Compression::Best);
        // rigidlab's mark (crate::files::Mark::Png): a later study replaces this plot only.
        enc.add_text_chunk("Software".to_string(), "rigidlab".to_string())
            .map_err(|e| e.to_string())?;
        let mut writer = enc.write_header().map_err(|e| e.to_string())?;
        writer
            .write_image_data(&indices)
            .map_err(|e| e.to_string())?;
        writer.finish().map_err(|e| e.to_string())?;
    }
    Ok(out)
}

/// Draws each engine's Pareto front: a dashed line through it and a ring (rapier) or a triangle
/// (Box2D) at each of its points, named in the legend.
fn draw_fronts<'a, DB: DrawingBackend + 'a>(
    chart: &mut ChartContext<'a, DB, Cartesian2d<LogCoord<f64>, LogCoord<f64>>>,
    p: &Panel,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    let clamp = |(c, e): (f64, f64)| (c, e.max(p.floor));
    for f in &p.fronts {
        let front: Vec<(f64, f64)> = f.points.iter().cloned().map(clamp).collect();
        let style = f
            .color
            .mix(0.7)
            .stroke_width(if f.marker == Marker::Circle { 1 } else { 2 });
        if front.len() > 1 {
            chart
                .draw_series(DashedLineSeries::new(
                    front.clone(),
                    6,
                    4,
                    f.color.mix(0.6).stroke_width(2),
                ))
                .map_err(err)?;
        }
        let anno = match f.marker {
            Marker::Circle => chart.draw_series(front.iter().map(|pt| Circle::new(*pt, 9, style))),
            Marker::Triangle => {
                chart.draw_series(front.iter().map(|pt| TriangleMarker::new(*pt, 9, style)))
            }
        }
        .map_err(err)?;
        let marker = f.marker;
        anno.label(f.label.as_str())
            .legend(move |(x, y)| match marker {
                Marker::Circle => Circle::new((x + 10, y), 6, style).into_dyn(),
                Marker::Triangle => TriangleMarker::new((x + 10, y), 6, style).into_dyn(),
            });
    }
    Ok(())
}

fn draw_on<DB: DrawingBackend>(
    root: DrawingArea<DB, plotters::coord::Shift>,
    caption: &str,
    panels: &[Panel],
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let root = root
        .titled(caption, ("sans-serif", 20).into_font())
        .map_err(err)?;
    let areas = root.split_evenly((1, panels.len().max(1)));
    for (area, p) in areas.into_iter().zip(panels) {
        let clamp = |(c, e): (f64, f64)| (c, e.max(p.floor));
        let all: Vec<(f64, f64)> = p
            .curves
            .iter()
            .flat_map(|c| c.points.iter().cloned())
            .filter(|(c, e)| c.is_finite() && e.is_finite() && *c > 0.0)
            .map(clamp)
            .collect();
        if all.is_empty() {
            area.draw(&Text::new(
                format!("{}: nothing to plot", p.title),
                (20, 40),
                ("sans-serif", 16).into_font(),
            ))
            .map_err(err)?;
            continue;
        }
        let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
        for (x, y) in &all {
            x0 = x0.min(*x);
            x1 = x1.max(*x);
            y0 = y0.min(*y);
            y1 = y1.max(*y);
        }
        let (x0, x1) = (x0 / 1.4, x1 * 1.4);
        // Room above for the legend; at least a factor 10 of range so a flat curve still reads.
        let (y0, y1) = (y0 / 1.5, (y1 * 4.0).max(y0 * 10.0));
        let mut chart = ChartBuilder::on(&area)
            .caption(&p.title, ("sans-serif", 16).into_font())
            .margin(12)
            .x_label_area_size(44)
            .y_label_area_size(64)
            .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
            .map_err(err)?;
        chart
            .configure_mesh()
            .x_desc("cost: µs of stepping per simulated second")
            .y_desc(p.y_desc.as_str())
            .x_label_formatter(&sci)
            .y_label_formatter(&sci)
            .label_style(("sans-serif", 13).into_font())
            .axis_desc_style(("sans-serif", 14).into_font())
            .light_line_style(WHITE.mix(0.0))
            .draw()
            .map_err(err)?;
        draw_fronts(&mut chart, p)?;
        if !p.meets.is_empty() {
            chart
                .draw_series(
                    p.meets
                        .iter()
                        .cloned()
                        .map(clamp)
                        .map(|pt| Circle::new(pt, 6, RGBColor(0, 170, 0).stroke_width(2))),
                )
                .map_err(err)?
                .label("meets the level's tolerance")
                .legend(|(x, y)| Circle::new((x + 10, y), 5, RGBColor(0, 170, 0).stroke_width(2)));
        }
        for c in &p.curves {
            let pts: Vec<(f64, f64)> = c
                .points
                .iter()
                .cloned()
                .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0)
                .map(clamp)
                .collect();
            if pts.is_empty() {
                continue;
            }
            let color = c.color;
            // A second engine's curves dashed, beside the first's solid ones.
            match c.marker {
                Marker::Circle => {
                    chart.draw_series(LineSeries::new(pts.clone(), color.stroke_width(2)))
                }
                Marker::Triangle => chart.draw_series(DashedLineSeries::new(
                    pts.clone(),
                    8,
                    4,
                    color.stroke_width(2),
                )),
            }
            .map_err(err)?
            .label(c.label.as_str())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(2))
            });
            match c.marker {
                Marker::Circle => {
                    chart.draw_series(pts.iter().map(|pt| Circle::new(*pt, 3, color.filled())))
                }
                Marker::Triangle => chart.draw_series(
                    pts.iter()
                        .map(|pt| TriangleMarker::new(*pt, 5, color.filled())),
                ),
            }
            .map_err(err)?;
        }
        for (label, pt) in &p.marks {
            let pt = clamp(*pt);
            if !(pt.0.is_finite() && pt.1.is_finite()) {
                continue;
            }
            chart
                .draw_series(std::iter::once(Cross::new(pt, 7, BLACK.stroke_width(2))))
                .map_err(err)?;
            chart
                .draw_series(std::iter::once(Text::new(
                    label.clone(),
                    pt,
                    ("sans-serif", 12).into_font(),
                )))
                .map_err(err)?;
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK.mix(0.3))
            .label_font(("sans-serif", 12).into_font())
            .draw()
            .map_err(err)?;
    }
    root.present().map_err(err)?;
    Ok(())
}
