//! `eigenrad verify`'s curves as SVG: error against the mode count, one plot per metric.

use std::path::PathBuf;

use plotters::prelude::*;

use super::{CaseKind, Metric, VerifyReport};
use crate::error::{Error, Result};

/// Errors under this are drawn at it on the log axis (the exact end of the curves).
pub const PLOT_FLOOR: f64 = 1e-9;

/// One SVG per metric (error vs p, log-log; one curve per case kind and formulation, the
/// worst case of the kind), with its file name `<scene>-<metric>.svg`.
pub fn svgs(r: &VerifyReport) -> Result<Vec<(String, String)>> {
    let mut out = Vec::new();
    for metric in Metric::ALL {
        let has = match metric {
            Metric::Patches => true,
            Metric::Zones => !r.zones.is_empty(),
            Metric::Sensors => !r.sensors.is_empty(),
        };
        if !has {
            continue;
        }
        let name = format!("{}-{}.svg", r.scene, metric.label());
        let svg = plot(r, metric).map_err(|e| Error::Io {
            path: PathBuf::from(&name),
            reason: std::io::Error::other(e),
        })?;
        out.push((name, svg));
    }
    Ok(out)
}

/// One curve: legend label, case kind (colour), split (solid) or seed (dashed), (p, error).
type Series = (String, usize, bool, Vec<(f64, f64)>);

fn plot(r: &VerifyReport, metric: Metric) -> std::result::Result<String, String> {
    let colors = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
    ];
    let mut series: Vec<Series> = Vec::new();
    for (fi, f) in r.formulations.iter().enumerate() {
        for (ki, k) in CaseKind::ALL.iter().enumerate() {
            let points: Option<Vec<(f64, f64)>> = r
                .modes
                .iter()
                .enumerate()
                .map(|(t, &p)| {
                    f.worst(Some(*k), metric, t)
                        .map(|e| (p as f64, e.max(PLOT_FLOOR)))
                })
                .collect();
            if let Some(points) = points {
                series.push((
                    format!("{}, {}", f.formulation, k.label()),
                    ki,
                    fi == 0,
                    points,
                ));
            }
        }
    }
    let top = series
        .iter()
        .flat_map(|s| s.3.iter().map(|p| p.1))
        .fold(PLOT_FLOOR * 10.0, f64::max)
        * 2.0;
    let p_max = r.modes.last().copied().unwrap_or(1).max(2) as f64;
    let title = format!(
        "{}: {} error vs modes p (errors < {PLOT_FLOOR:.0e} drawn at it)",
        r.scene,
        metric.label()
    );
    crate::picture::register_font();
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, (800, 520)).into_drawing_area();
        root.fill(&WHITE).map_err(|e| e.to_string())?;
        let mut chart = ChartBuilder::on(&root)
            .caption(title, ("sans-serif", 18))
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(70)
            .build_cartesian_2d((1.0..p_max).log_scale(), (PLOT_FLOOR..top).log_scale())
            .map_err(|e| e.to_string())?;
        chart
            .configure_mesh()
            .x_desc("modes p")
            .y_desc("relative error")
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .x_label_formatter(&|v| format!("{v:.0}"))
            .draw()
            .map_err(|e| e.to_string())?;
        for (label, kind, split, points) in series {
            let color = colors[kind % colors.len()];
            if split {
                chart
                    .draw_series(LineSeries::new(points, color.stroke_width(2)).point_size(3))
                    .map_err(|e| e.to_string())?
                    .label(label)
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 24, y)], color.stroke_width(2))
                    });
            } else {
                chart
                    .draw_series(DashedLineSeries::new(points, 6, 4, color.stroke_width(1)))
                    .map_err(|e| e.to_string())?
                    .label(label)
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 8, y)], color.stroke_width(1))
                    });
            }
        }
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::LowerLeft)
            .background_style(WHITE.mix(0.85))
            .border_style(BLACK)
            .draw()
            .map_err(|e| e.to_string())?;
        root.present().map_err(|e| e.to_string())?;
    }
    Ok(svg)
}
