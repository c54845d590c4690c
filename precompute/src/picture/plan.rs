//! The plan of a work plane: its calculation grid's cells in false colour, isolux lines at
//! round values, the room's outline, the luminaires above, axes in metres, a colour bar and
//! the grid's figures.
//!
//! The picture shows the calculation grid itself (EN 12464-1's cells, each in the colour of
//! the value at its centre point), not a finer interpolation: those are the values the
//! figures `E_avg`, `E_min` and `U_o` are taken of, the values a basis carries, and the ones
//! `eval` and `solve` print. The isolux lines are interpolated linearly between the points
//! ([`super::contour`]), so they run through the cells between the points' values.

use plotters::prelude::*;

use super::colour::Scale;
use super::contour::{isolines, Lattice};
use super::draw::{self, failed, format_value, rgb, Extras, Frame};

/// One work plane's calculation grid on a plan; positions in m, values in the plan's `unit`.
#[derive(Clone, Debug)]
pub struct PlanGrid {
    /// The zone's name.
    pub zone: String,
    /// Grid points along x and y.
    pub counts: [usize; 2],
    /// Cell sides along x and y, m; the points sit at the cells' centres.
    pub cell: [f64; 2],
    /// Band left out at the walls, m.
    pub border: f64,
    /// Every point's `(x, y)`, x fastest, m (points inside obstacles or outside the floor
    /// are not among them).
    pub points: Vec<[f64; 2]>,
    /// Every point's value.
    pub values: Vec<f64>,
    /// `E_avg`, `E_min`, `E_max`, `U_o` of the grid, as `eval` or `solve` report them.
    pub figures: [f64; 4],
}

/// A block seen from above: its footprint, and whether it stands through the work plane.
#[derive(Clone, Copy, Debug)]
pub struct Footprint {
    /// Lowest and highest corner `(x, y)`, m.
    pub corners: [[f64; 2]; 2],
    /// Its top is above the work plane (a column, a cabinet): the plane has no points there,
    /// and the footprint is filled. Lower blocks (desks) are outlined over the cells.
    pub through: bool,
}

/// What a plan shows; positions in m, values in `unit`.
#[derive(Clone, Debug)]
pub struct PlanInput {
    /// First line of the caption (scene, zones, height).
    pub title: String,
    /// Further caption lines under the figures (what was computed, the levels).
    pub notes: Vec<String>,
    /// Unit of the values: `lux`, `fc` or `W/m²`.
    pub unit: &'static str,
    /// The work planes drawn (several zones of one floor at once), on one colour scale.
    pub grids: Vec<PlanGrid>,
    /// The drawn extent: lowest and highest corner `(x, y)`, m.
    pub room: [[f64; 2]; 2],
    /// The floor seen from above: its patches' outlines `(x, y)`, m (the floor polygon of any
    /// room, less what stands on it); empty to draw the extent's rectangle instead.
    pub floor: Vec<Vec<[f64; 2]>>,
    /// The rooms' walls seen from above: each room's plan, a closed outline `(x, y)`, m;
    /// empty to outline the extent's rectangle.
    pub walls: Vec<Vec<[f64; 2]>>,
    /// Windows in the walls seen from above: each a segment `(x, y)`, m.
    pub windows: Vec<[[f64; 2]; 2]>,
    /// Other openings in the walls (doors, wall panels) seen from above, segments, m.
    pub doors: Vec<[[f64; 2]; 2]>,
    /// Blocks inside the rooms seen from above.
    pub blocks: Vec<Footprint>,
    /// Outlines of luminaires seen from above (lowest and highest corner), m.
    pub luminaires: Vec<[[f64; 2]; 2]>,
    /// Positions of luminaires with photometry (point sources), m.
    pub luminaire_points: Vec<[f64; 2]>,
    /// Positions of the sensors, m.
    pub sensors: Vec<[f64; 2]>,
}

/// Colours of what a plan draws besides the light (the tests read them back).
pub mod colours {
    use super::super::colour::Rgb;
    /// The picture's background, and where no floor is (an L's notch).
    pub const BACKGROUND: Rgb = [255, 255, 255];
    /// The floor where the work plane has no point (the border band).
    pub const FLOOR: Rgb = [235, 235, 235];
    /// A block standing through the work plane (a column).
    pub const BLOCK: Rgb = [110, 110, 110];
    /// A lower block's outline (a desk), and doors.
    pub const FURNITURE: Rgb = [150, 90, 30];
    /// Windows.
    pub const WINDOW: Rgb = [40, 150, 230];
    /// Walls, luminaires and isolux lines' labels' frames.
    pub const INK: Rgb = [0, 0, 0];
    /// Sensors.
    pub const SENSOR: Rgb = [220, 30, 30];
}

/// A plan ready to draw: its input, colour scale and isolux lines.
#[derive(Clone, Debug)]
pub struct Plan {
    /// What it shows.
    pub input: PlanInput,
    /// The value-to-colour map, over the grid's values in round numbers.
    pub scale: Scale,
    /// The isolux lines: each round value of the scale strictly between the grid's lowest and
    /// highest value, with its polylines (m); none for a uniform grid
    /// ([`Scale::is_uniform`]).
    pub isolux: Vec<(f64, Vec<Vec<[f64; 2]>>)>,
}

/// A grid's points on their full lattice: its first corner (m), its counts, its spacing (m)
/// and a value per lattice point, NaN where the grid has no point (outside the floor of an L,
/// inside a column), so that isolux lines stop there. `None` without points.
fn full_lattice(g: &PlanGrid) -> Option<FullLattice> {
    let [dx, dy] = g.cell;
    if g.points.is_empty() || !(dx > 0.0 && dy > 0.0) {
        return None;
    }
    let x0 = g.points.iter().map(|p| p[0]).fold(f64::INFINITY, f64::min);
    let y0 = g.points.iter().map(|p| p[1]).fold(f64::INFINITY, f64::min);
    let index = |p: &[f64; 2]| {
        (
            ((p[0] - x0) / dx).round() as usize,
            ((p[1] - y0) / dy).round() as usize,
        )
    };
    let nx = g.points.iter().map(|p| index(p).0).max()? + 1;
    let ny = g.points.iter().map(|p| index(p).1).max()? + 1;
    let mut values = vec![f64::NAN; nx * ny];
    for (p, &v) in g.points.iter().zip(&g.values) {
        let (i, j) = index(p);
        values[j * nx + i] = v;
    }
    Some(FullLattice {
        origin: [x0, y0],
        counts: [nx, ny],
        spacing: [dx, dy],
        values,
    })
}

/// A [`Lattice`] that owns its values.
struct FullLattice {
    origin: [f64; 2],
    counts: [usize; 2],
    spacing: [f64; 2],
    values: Vec<f64>,
}

/// Pixels per metre at most, and the plan's largest drawing, pixels.
const MAX_SCALE: f64 = 160.0;
const MAX_PLOT: (f64, f64) = (640.0, 440.0);

impl Plan {
    /// The plan of `input`: the scale spans its values, the isolux lines are at the scale's
    /// round values inside them.
    pub fn new(input: PlanInput) -> Plan {
        let values = input.grids.iter().flat_map(|g| &g.values);
        let (lo, hi) = values
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        let (lo, hi) = if lo <= hi { (lo, hi) } else { (0.0, 0.0) };
        let scale = Scale::around(lo, hi, input.unit);
        let lattices: Vec<_> = input.grids.iter().filter_map(full_lattice).collect();
        let isolux = scale
            .isolux_levels(lo, hi)
            .into_iter()
            .map(|t| {
                let lines = lattices
                    .iter()
                    .flat_map(|l| {
                        let lattice = Lattice {
                            counts: l.counts,
                            origin: l.origin,
                            spacing: l.spacing,
                            values: &l.values,
                        };
                        isolines(&lattice, t)
                    })
                    .collect::<Vec<_>>();
                (t, lines)
            })
            .filter(|(_, lines)| !lines.is_empty())
            .collect();
        Plan {
            input,
            scale,
            isolux,
        }
    }

    /// The plan as an SVG document, and where its metres lie in its pixels.
    pub fn svg(&self) -> Result<(String, Frame), String> {
        draw::svg(self.size(), |root| self.draw(root))
    }

    /// The plan as PNG bytes, and where its metres lie in its pixels.
    pub fn png(&self) -> Result<(Vec<u8>, Frame), String> {
        draw::png(self.size(), |root| self.draw(root))
    }

    /// The drawn range, m: the room with a small margin.
    fn range(&self) -> ([f64; 2], [f64; 2]) {
        let [[x0, y0], [x1, y1]] = self.input.room;
        let pad = 0.03 * (x1 - x0).max(y1 - y0).max(1e-3);
        ([x0 - pad, x1 + pad], [y0 - pad, y1 + pad])
    }

    /// The plot's size in pixels: metres drawn at one scale on both axes.
    fn plot_size(&self) -> (u32, u32) {
        draw::plot_size(self.range(), MAX_PLOT, MAX_SCALE)
    }

    const TITLE: u32 = 40;
    const LEFT: u32 = 10 + 55;
    const RIGHT: u32 = 15;
    const BAR: u32 = 130;
    const BELOW: u32 = 10 + 45;
    const LINE: u32 = 20;

    fn caption(&self) -> Vec<String> {
        let i = &self.input;
        let u = i.unit;
        let fmt = |v: f64| format_value(v, self.scale.step / 100.0);
        let mut lines = Vec::new();
        for g in &i.grids {
            let [avg, min, max, uo] = g.figures;
            // Several zones: each line names its zone.
            let zone = if i.grids.len() > 1 {
                format!("{}: ", g.zone)
            } else {
                String::new()
            };
            lines.push(format!(
                "{zone}E_avg {} {u}   E_min {} {u}   E_max {} {u}   U_o = E_min/E_avg {uo:.2}",
                fmt(avg),
                fmt(min),
                fmt(max)
            ));
            lines.push(format!(
                "{zone}{} × {} points (EN 12464-1), cells {:.2} × {:.2} m, border {:.2} m left out; each cell in the colour of its point",
                g.counts[0], g.counts[1], g.cell[0], g.cell[1], g.border
            ));
        }
        if !self.isolux.is_empty() {
            lines.push(format!(
                "isolux lines every {} {u}, linear between points",
                format_value(self.scale.step, self.scale.step)
            ));
        }
        match (i.luminaires.is_empty(), i.luminaire_points.is_empty()) {
            (false, false) => lines.push(
                "dashed: emitting surfaces seen from above; +: luminaires with photometry".into(),
            ),
            (false, true) => lines.push("dashed: emitting surfaces seen from above".into()),
            (true, false) => lines.push("+: luminaires with photometry".into()),
            (true, true) => {}
        }
        let mut marks = Vec::new();
        if !i.walls.is_empty() {
            marks.push("walls black");
        }
        if !i.windows.is_empty() {
            marks.push("windows blue");
        }
        if !i.doors.is_empty() {
            marks.push("doors and other openings brown");
        }
        if i.blocks.iter().any(|b| b.through) {
            marks.push("blocks through the work plane dark grey");
        }
        if i.blocks.iter().any(|b| !b.through) {
            marks.push("lower blocks outlined in brown");
        }
        if !i.sensors.is_empty() {
            marks.push("sensors red dots");
        }
        if !marks.is_empty() {
            lines.push(marks.join("; "));
        }
        lines.extend(i.notes.iter().cloned());
        draw::wrap(
            &lines,
            Self::LEFT + self.plot_size().0 + Self::RIGHT + Self::BAR - 20,
            14,
        )
    }

    fn size(&self) -> (u32, u32) {
        let (w, h) = self.plot_size();
        (
            Self::LEFT + w + Self::RIGHT + Self::BAR,
            Self::TITLE + 10 + h + Self::BELOW + Self::LINE * self.caption().len() as u32 + 10,
        )
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<Frame, String> {
        let i = &self.input;
        let (w, h) = self.plot_size();
        root.fill(&rgb(colours::BACKGROUND)).map_err(failed)?;
        let (top, rest) = root.split_vertically(Self::TITLE);
        draw::lines(&top, std::slice::from_ref(&i.title), (10, 12), 18, 0)?;
        let (middle, foot) = rest.split_vertically(10 + h + Self::BELOW);
        let (left, right) = middle.split_horizontally(Self::LEFT + w + Self::RIGHT);
        let (xr, yr) = self.range();
        let mut chart = ChartBuilder::on(&left)
            .margin_left(10)
            .margin_right(Self::RIGHT)
            .margin_top(10)
            .margin_bottom(10)
            .x_label_area_size(45)
            .y_label_area_size(55)
            .build_cartesian_2d(xr[0]..xr[1], yr[0]..yr[1])
            .map_err(failed)?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("x (m)")
            .y_desc("y (m)")
            .label_style(draw::text(13))
            .axis_desc_style(draw::text(14))
            .x_label_formatter(&|v| format!("{v:.1}"))
            .y_label_formatter(&|v| format!("{v:.1}"))
            .draw()
            .map_err(failed)?;
        let [[rx0, ry0], [rx1, ry1]] = i.room;
        // The floor, whose border band is not evaluated, in light grey; then the cells over it.
        if i.floor.is_empty() {
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(rx0, ry0), (rx1, ry1)],
                    rgb(colours::FLOOR).filled(),
                )))
                .map_err(failed)?;
        } else {
            chart
                .draw_series(i.floor.iter().map(|patch| {
                    Polygon::new(
                        patch.iter().map(|c| (c[0], c[1])).collect::<Vec<_>>(),
                        rgb(colours::FLOOR).filled(),
                    )
                }))
                .map_err(failed)?;
        }
        for g in &i.grids {
            let [dx, dy] = g.cell;
            chart
                .draw_series(g.points.iter().zip(&g.values).map(|(p, &v)| {
                    Rectangle::new(
                        [
                            (p[0] - dx / 2.0, p[1] - dy / 2.0),
                            (p[0] + dx / 2.0, p[1] + dy / 2.0),
                        ],
                        rgb(self.scale.colour(Some(v))).filled(),
                    )
                }))
                .map_err(failed)?;
        }
        // Blocks: those standing through the plane filled, lower ones outlined over the cells.
        for b in &i.blocks {
            let [[a, c], [d, e]] = b.corners;
            let style = if b.through {
                rgb(colours::BLOCK).filled()
            } else {
                rgb(colours::FURNITURE).stroke_width(2)
            };
            chart
                .draw_series(std::iter::once(Rectangle::new([(a, c), (d, e)], style)))
                .map_err(failed)?;
        }
        // Luminaires: dashed outlines and crosses.
        for &[[a, b], [c, d]] in &i.luminaires {
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(a, b), (c, b), (c, d), (a, d), (a, b)],
                    5,
                    4,
                    rgb(colours::INK).stroke_width(1),
                ))
                .map_err(failed)?;
        }
        let arm = 0.015 * (rx1 - rx0).max(ry1 - ry0);
        for &[x, y] in &i.luminaire_points {
            for line in [
                vec![(x - arm, y), (x + arm, y)],
                vec![(x, y - arm), (x, y + arm)],
            ] {
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        line,
                        rgb(colours::INK).stroke_width(2),
                    )))
                    .map_err(failed)?;
            }
        }
        // Isolux lines, labelled at their middle vertex.
        let line = RGBColor(20, 20, 20);
        let mut labels = Vec::new();
        for (level, polylines) in &self.isolux {
            for poly in polylines {
                chart
                    .draw_series(std::iter::once(PathElement::new(
                        poly.iter().map(|p| (p[0], p[1])).collect::<Vec<_>>(),
                        line.stroke_width(2),
                    )))
                    .map_err(failed)?;
                let mid = poly[poly.len() / 2];
                labels.push((format_value(*level, self.scale.step), mid));
            }
        }
        // The walls, then the openings in them over the walls' lines.
        if i.walls.is_empty() {
            chart
                .draw_series(std::iter::once(Rectangle::new(
                    [(rx0, ry0), (rx1, ry1)],
                    rgb(colours::INK).stroke_width(2),
                )))
                .map_err(failed)?;
        }
        for outline in &i.walls {
            let mut closed: Vec<(f64, f64)> = outline.iter().map(|c| (c[0], c[1])).collect();
            closed.extend(closed.first().copied());
            chart
                .draw_series(std::iter::once(PathElement::new(
                    closed,
                    rgb(colours::INK).stroke_width(3),
                )))
                .map_err(failed)?;
        }
        for (segments, colour) in [
            (&i.windows, rgb(colours::WINDOW)),
            (&i.doors, rgb(colours::FURNITURE)),
        ] {
            chart
                .draw_series(segments.iter().map(|&[a, b]| {
                    PathElement::new(vec![(a[0], a[1]), (b[0], b[1])], colour.stroke_width(6))
                }))
                .map_err(failed)?;
        }
        chart
            .draw_series(
                i.sensors
                    .iter()
                    .map(|&[x, y]| Circle::new((x, y), 5, rgb(colours::SENSOR).filled())),
            )
            .map_err(failed)?;
        let frame = Frame::of(&chart, xr, yr);
        let (origin_x, origin_y) = root.get_base_pixel();
        for (label, [x, y]) in labels {
            let (c, r) = chart.backend_coord(&(x, y));
            draw::boxed_label(root, &label, (c - origin_x, r - origin_y), 12)?;
        }
        // The colour bar beside the plot, as tall as it.
        let (_, plot_rows) = chart.plotting_area().get_pixel_range();
        let (_, base_row) = right.get_base_pixel();
        draw::colour_bar(
            &right,
            &self.scale,
            plot_rows.start - base_row,
            plot_rows.end - plot_rows.start,
            Extras::default(),
        )?;
        draw::lines(&foot, &self.caption(), (10, 4), 14, Self::LINE as i32)?;
        Ok(frame)
    }
}
