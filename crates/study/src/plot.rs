//! Plots of a study: per scene, relative RMSE against N and against time
//! (seconds per estimate, one thread), log-log, one line per strategy ×
//! sequence, with an N^-½ guide; SVG and PNG, text in DejaVu Sans embedded
//! in the binary (no system fonts needed).

use std::path::Path;
use std::sync::Once;

use crate::results::ResultRow;
use plotters::coord::Shift;
use plotters::prelude::*;

static FONT: Once = Once::new();

fn register_font() {
    FONT.call_once(|| {
        // The font is valid TTF shipped by the dejavu crate; a failure here
        // would only lose the plots' text.
        let _ = plotters::style::register_font(
            "sans-serif",
            FontStyle::Normal,
            dejavu::sans::regular(),
        );
    });
}

/// One line: its label and its points (N, seconds per estimate, relative
/// RMSE), relative RMSE > 0 only.
struct Line {
    label: String,
    points: Vec<(f64, f64, f64)>,
}

fn lines_of(rows: &[&ResultRow]) -> Vec<Line> {
    let mut lines: Vec<Line> = Vec::new();
    for r in rows {
        let label = format!(
            "{} / {}",
            r.strategy,
            crate::results::sequence_label(r.sequence, r.precision)
        );
        let idx = match lines.iter().position(|l| l.label == label) {
            Some(i) => i,
            None => {
                lines.push(Line {
                    label,
                    points: Vec::new(),
                });
                lines.len() - 1
            }
        };
        if let Some(e) = r.stats.rel_rmse.filter(|&e| e > 0.0) {
            let n = r.n() as f64;
            lines[idx]
                .points
                .push((n, n * r.stats.ns_per_sample * 1e-9, e));
        }
    }
    lines
}

fn panel<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    title: &str,
    lines: &[Line],
    by_time: bool,
) -> Result<(), String> {
    let x = |p: &(f64, f64, f64)| if by_time { p.1 } else { p.0 };
    let all: Vec<&(f64, f64, f64)> = lines.iter().flat_map(|l| &l.points).collect();
    if all.is_empty() {
        return Ok(());
    }
    let (mut x0, mut x1, mut y0, mut y1) = (f64::MAX, f64::MIN, f64::MAX, f64::MIN);
    for p in &all {
        x0 = x0.min(x(p));
        x1 = x1.max(x(p));
        y0 = y0.min(p.2);
        y1 = y1.max(p.2);
    }
    let (x0, x1, y0, y1) = (x0 / 1.5, x1 * 1.5, y0 / 3.0, y1 * 3.0);
    let mut chart = ChartBuilder::on(area)
        .caption(title, ("sans-serif", 18))
        .margin(10)
        .x_label_area_size(40)
        .y_label_area_size(60)
        .build_cartesian_2d((x0..x1).log_scale(), (y0..y1).log_scale())
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(if by_time {
            "seconds per estimate (one thread)"
        } else {
            "samples N"
        })
        .y_desc("relative RMSE")
        .x_label_formatter(&|v| format!("{v:.0e}"))
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .label_style(("sans-serif", 12))
        .draw()
        .map_err(|e| e.to_string())?;
    // The N^-½ guide through the largest first point.
    let start = lines
        .iter()
        .filter_map(|l| l.points.first())
        .max_by(|a, b| a.2.total_cmp(&b.2))
        .copied()
        .unwrap_or((1.0, 1.0, 1.0));
    let guide: Vec<(f64, f64)> = (0..=40)
        .map(|i| {
            let t = x0 * (x1 / x0).powf(f64::from(i) / 40.0);
            (t, start.2 * (t / x(&start)).powf(-0.5))
        })
        .filter(|p| p.1 >= y0 && p.1 <= y1)
        .collect();
    chart
        .draw_series(LineSeries::new(guide, BLACK.mix(0.4).stroke_width(2)))
        .map_err(|e| e.to_string())?
        .label(if by_time { "∝ t^-½" } else { "∝ N^-½" })
        .legend(|(x, y)| PathElement::new(vec![(x, y), (x + 15, y)], BLACK.mix(0.4)));
    // One colour per strategy, one width per sequence (thin: independent,
    // medium: stratified, thick: Sobol).
    const COLOURS: [RGBColor; 6] = [
        RGBColor(214, 39, 40),
        RGBColor(31, 119, 180),
        RGBColor(44, 160, 44),
        RGBColor(148, 103, 189),
        RGBColor(255, 127, 14),
        RGBColor(140, 86, 75),
    ];
    let mut strategies: Vec<&str> = Vec::new();
    for l in lines {
        if l.points.is_empty() {
            continue;
        }
        let strategy = l.label.split(" / ").next().unwrap_or("");
        let i = match strategies.iter().position(|s| *s == strategy) {
            Some(i) => i,
            None => {
                strategies.push(strategy);
                strategies.len() - 1
            }
        };
        let color = COLOURS[i % COLOURS.len()].to_rgba();
        let width = match l.label.rsplit(" / ").next() {
            Some("independent") => 1,
            Some("stratified") => 2,
            _ => 4,
        };
        chart
            .draw_series(LineSeries::new(
                l.points.iter().map(|p| (x(p), p.2)),
                color.stroke_width(width),
            ))
            .map_err(|e| e.to_string())?
            .label(l.label.clone())
            .legend(move |(x, y)| {
                PathElement::new(vec![(x, y), (x + 15, y)], color.stroke_width(width))
            });
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::LowerLeft)
        .label_font(("sans-serif", 10))
        .background_style(WHITE.mix(0.8))
        .border_style(BLACK.mix(0.3))
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(())
}

fn figure<DB: DrawingBackend>(
    root: DrawingArea<DB, Shift>,
    scene: &str,
    lines: &[Line],
) -> Result<(), String> {
    root.fill(&WHITE).map_err(|e| e.to_string())?;
    let (left, right) = root.split_horizontally(root.dim_in_pixel().0 / 2);
    panel(&left, &format!("{scene}: error against N"), lines, false)?;
    panel(&right, &format!("{scene}: error against time"), lines, true)?;
    root.present().map_err(|e| e.to_string())
}

/// Writes `plots/<scene>.svg` and `plots/<scene>.png` into `out` for every
/// scene with a closed form (the others have no error to plot). Exact
/// (zero-error) lines are left out: a log scale has no 0.
pub fn write_plots(out: &Path, rows: &[ResultRow]) -> Result<(), String> {
    register_font();
    let dir = out.join("plots");
    let mut scenes: Vec<&str> = Vec::new();
    for r in rows {
        if r.reference.is_some() && !scenes.contains(&r.scene.as_str()) {
            scenes.push(&r.scene);
        }
    }
    if scenes.is_empty() {
        return Ok(());
    }
    std::fs::create_dir_all(&dir).map_err(|e| format!("cannot create {}: {e}", dir.display()))?;
    for scene in scenes {
        let mut mine: Vec<&ResultRow> = rows.iter().filter(|r| r.scene == scene).collect();
        mine.sort_by_key(|r| r.row);
        let lines = lines_of(&mine);
        let size = (1400, 560);
        let svg = dir.join(format!("{scene}.svg"));
        figure(
            SVGBackend::new(&svg, size).into_drawing_area(),
            scene,
            &lines,
        )
        .map_err(|e| format!("{}: {e}", svg.display()))?;
        let png = dir.join(format!("{scene}.png"));
        figure(
            BitMapBackend::new(&png, size).into_drawing_area(),
            scene,
            &lines,
        )
        .map_err(|e| format!("{}: {e}", png.display()))?;
    }
    Ok(())
}
