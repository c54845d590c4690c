//! The room's surfaces unfolded: every patch in false colour on a net of the box around the
//! scene, the floor in the middle seen from above, each wall folded out around its floor
//! edge (so seen from inside the room), and the ceiling folded out beyond the east wall's top
//! edge, seen from below.
//!
//! An unfolded view rather than an axonometric one: every wall, the floor and the ceiling are
//! seen whole, face-on and at one scale, with nothing in front of them but what stands in the
//! room, where an axonometric view must leave out or cut away the walls nearest the viewer.
//! Each patch is drawn once, on the panel its normal faces most (a patch facing up on the
//! floor's, one facing +y on the wall at the lowest y, ...), projected straight onto it, the
//! patches nearest the viewer last: a desk's top covers the floor under it, a desk's side the
//! wall behind it, as seen from inside the room.

use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::colour::Scale;
use super::draw::{self, failed, rgb, Extras, Frame};

/// One patch: its corners (m), unit normal, value (`None`: none known) and whether it emits
/// light (its value may then lie above the scale, which the other patches set).
#[derive(Clone, Debug)]
pub struct NetPatch {
    /// Corners, m.
    pub vertices: Vec<[f64; 3]>,
    /// Unit normal, towards the side that receives light.
    pub normal: [f64; 3],
    /// Illuminance or luminance, in the net's unit.
    pub value: Option<f64>,
    /// Whether the patch emits (a luminaire, a window): left out of the scale's range.
    pub emits: bool,
}

/// What the surfaces' picture shows.
#[derive(Clone, Debug)]
pub struct NetInput {
    /// First line of the caption.
    pub title: String,
    /// Further caption lines (what was computed, the levels).
    pub notes: Vec<String>,
    /// Unit of the values: `lux`, `fc`, `W/m²`, `cd/m²`, `W/(m²·sr)`.
    pub unit: &'static str,
    /// What the values are, for the caption: `illuminance E`, `luminance L = M/π`.
    pub quantity: &'static str,
    /// The patches.
    pub patches: Vec<NetPatch>,
}

/// The six panels of the net.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub enum Panel {
    /// Patches facing up, seen from above.
    Floor,
    /// Patches facing +y: the wall at the lowest y, seen from inside.
    South,
    /// Patches facing −y: the wall at the highest y.
    North,
    /// Patches facing +x: the wall at the lowest x.
    West,
    /// Patches facing −x: the wall at the highest x.
    East,
    /// Patches facing down, seen from below.
    Ceiling,
}

impl Panel {
    /// The panel a normal faces most: its largest component, ties to z, then y, then x.
    pub fn of(n: [f64; 3]) -> Panel {
        let [ax, ay, az] = n.map(f64::abs);
        if az >= ay && az >= ax {
            if n[2] >= 0.0 {
                Panel::Floor
            } else {
                Panel::Ceiling
            }
        } else if ay >= ax {
            if n[1] >= 0.0 {
                Panel::South
            } else {
                Panel::North
            }
        } else if n[0] >= 0.0 {
            Panel::West
        } else {
            Panel::East
        }
    }
}

/// The surfaces ready to draw: the box, every patch's panel and projected corners, the draw
/// order and the colour scale.
#[derive(Clone, Debug)]
pub struct Net {
    /// What it shows.
    pub input: NetInput,
    /// The box around every patch: lowest and highest corner, m.
    pub bounds: [[f64; 3]; 2],
    /// Each patch's panel.
    pub panels: Vec<Panel>,
    /// The value-to-colour map: the values of the patches that do not emit, in round numbers.
    pub scale: Scale,
    /// Patch indices in drawing order: panel by panel, farthest from the viewer first.
    order: Vec<usize>,
}

const MAX_SCALE: f64 = 80.0;
const MAX_PLOT: (f64, f64) = (1100.0, 640.0);

impl Net {
    /// The net of `input`'s patches.
    pub fn new(input: NetInput) -> Net {
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        for p in &input.patches {
            for v in &p.vertices {
                for k in 0..3 {
                    lo[k] = lo[k].min(v[k]);
                    hi[k] = hi[k].max(v[k]);
                }
            }
        }
        if lo[0] > hi[0] || lo[0].is_nan() {
            (lo, hi) = ([0.0; 3], [1.0; 3]);
        }
        let panels: Vec<Panel> = input.patches.iter().map(|p| Panel::of(p.normal)).collect();
        // Nearest the viewer last: the depth along the panel's viewing direction of the
        // patch's centre.
        let depth = |i: usize| {
            let p = &input.patches[i];
            let c = p
                .vertices
                .iter()
                .fold([0.0; 3], |a, v| [a[0] + v[0], a[1] + v[1], a[2] + v[2]]);
            let c = c.map(|x| x / p.vertices.len().max(1) as f64);
            match panels[i] {
                Panel::Floor => c[2],
                Panel::Ceiling => -c[2],
                Panel::South => c[1],
                Panel::North => -c[1],
                Panel::West => c[0],
                Panel::East => -c[0],
            }
        };
        let mut order: Vec<usize> = (0..input.patches.len()).collect();
        order.sort_by(|&a, &b| {
            panels[a]
                .cmp(&panels[b])
                .then(depth(a).total_cmp(&depth(b)))
                .then(a.cmp(&b))
        });
        let values = |emitting: bool| {
            input
                .patches
                .iter()
                .filter(move |p| emitting || !p.emits)
                .filter_map(|p| p.value.filter(|v| v.is_finite()))
        };
        let min = values(true).fold(f64::INFINITY, f64::min);
        let mut max = values(false).fold(f64::NEG_INFINITY, f64::max);
        if max == f64::NEG_INFINITY {
            max = values(true).fold(f64::NEG_INFINITY, f64::max);
        }
        let scale = if min <= max {
            Scale::around(min, max, input.unit)
        } else {
            Scale::around(0.0, 0.0, input.unit)
        };
        Net {
            input,
            bounds: [lo, hi],
            panels,
            scale,
            order,
        }
    }

    /// Where the point `p` (m) of a patch on `panel` lies on the net, m: the floor's corner
    /// at the lowest x and y at the origin, x to the right and y up.
    pub fn project(&self, panel: Panel, p: [f64; 3]) -> [f64; 2] {
        let [[x0, y0, z0], [x1, _, _]] = self.bounds;
        let (w, d, h) = self.sides();
        let (x, y, z) = (p[0] - x0, p[1] - y0, p[2] - z0);
        match panel {
            Panel::Floor => [x, y],
            Panel::South => [x, -z],
            Panel::North => [x, d + z],
            Panel::West => [-z, y],
            Panel::East => [w + z, y],
            Panel::Ceiling => [w + h + (x1 - p[0]), y],
        }
    }

    /// Where patch `i`'s centroid (the mean of its corners) lies on the net, m.
    pub fn centre(&self, i: usize) -> [f64; 2] {
        let p = &self.input.patches[i];
        let c = p
            .vertices
            .iter()
            .fold([0.0; 3], |a, v| [a[0] + v[0], a[1] + v[1], a[2] + v[2]]);
        self.project(
            self.panels[i],
            c.map(|x| x / p.vertices.len().max(1) as f64),
        )
    }

    /// Width (x), depth (y) and height (z) of the box, m.
    fn sides(&self) -> (f64, f64, f64) {
        let [lo, hi] = self.bounds;
        (hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2])
    }

    /// The net's outline on the panel: lowest and highest corner, m.
    fn panel_rect(&self, panel: Panel) -> [[f64; 2]; 2] {
        let (w, d, h) = self.sides();
        match panel {
            Panel::Floor => [[0.0, 0.0], [w, d]],
            Panel::South => [[0.0, -h], [w, 0.0]],
            Panel::North => [[0.0, d], [w, d + h]],
            Panel::West => [[-h, 0.0], [0.0, d]],
            Panel::East => [[w, 0.0], [w + h, d]],
            Panel::Ceiling => [[w + h, 0.0], [2.0 * w + h, d]],
        }
    }

    fn panel_label(&self, panel: Panel) -> String {
        let [lo, hi] = self.bounds;
        match panel {
            Panel::Floor => "floor".into(),
            Panel::Ceiling => "ceiling, seen from below".into(),
            Panel::South => format!("wall y = {:.2} m", lo[1]),
            Panel::North => format!("wall y = {:.2} m", hi[1]),
            Panel::West => format!("wall x = {:.2} m", lo[0]),
            Panel::East => format!("wall x = {:.2} m", hi[0]),
        }
    }

    /// The drawn range, m: the whole net with a small margin.
    fn range(&self) -> ([f64; 2], [f64; 2]) {
        let (w, d, h) = self.sides();
        let pad = 0.02 * (2.0 * w + 2.0 * h);
        // Room for a line of text above and below the net.
        let text = 0.07 * (d + 2.0 * h);
        (
            [-h - pad, 2.0 * w + h + pad],
            [-h - pad - text, d + h + pad + text],
        )
    }

    fn plot_size(&self) -> (u32, u32) {
        draw::plot_size(self.range(), MAX_PLOT, MAX_SCALE)
    }

    const TITLE: u32 = 40;
    const BAR: u32 = 150;
    const LINE: u32 = 20;

    fn extras(&self) -> Extras {
        let mut e = Extras::default();
        for p in &self.input.patches {
            match p.value {
                None => e.no_value = true,
                Some(v) if self.scale.bin(v).is_none() => e.above = true,
                Some(_) => {}
            }
        }
        e
    }

    fn caption(&self) -> Vec<String> {
        let mut lines = vec![
            format!(
                "{} per patch ({}); the floor in the middle seen from above, the walls folded out around its edges, the ceiling beyond the wall x = {:.2} m",
                self.input.quantity, self.input.unit, self.bounds[1][0]
            ),
            "the scale spans the patches that do not emit; each patch on the side it faces most, nearest on top".into(),
        ];
        lines.extend(self.input.notes.iter().cloned());
        draw::wrap(&lines, 20 + self.plot_size().0 + Self::BAR - 20, 14)
    }

    fn size(&self) -> (u32, u32) {
        let (w, h) = self.plot_size();
        (
            20 + w + Self::BAR,
            Self::TITLE + 10 + h + 10 + Self::LINE * self.caption().len() as u32 + 10,
        )
    }

    /// The surfaces as an SVG document, and where the net's metres lie in its pixels.
    pub fn svg(&self) -> Result<(String, Frame), String> {
        draw::svg(self.size(), |root| self.draw(root))
    }

    /// The surfaces as PNG bytes, and where the net's metres lie in its pixels.
    pub fn png(&self) -> Result<(Vec<u8>, Frame), String> {
        draw::png(self.size(), |root| self.draw(root))
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<Frame, String> {
        let (w, h) = self.plot_size();
        root.fill(&WHITE).map_err(failed)?;
        let (top, rest) = root.split_vertically(Self::TITLE);
        draw::lines(
            &top,
            std::slice::from_ref(&self.input.title),
            (10, 12),
            18,
            0,
        )?;
        let (middle, foot) = rest.split_vertically(10 + h + 10);
        let (left, right) = middle.split_horizontally(20 + w);
        let (xr, yr) = self.range();
        let mut chart = ChartBuilder::on(&left)
            .margin(10)
            .build_cartesian_2d(xr[0]..xr[1], yr[0]..yr[1])
            .map_err(failed)?;
        const PANELS: [Panel; 6] = [
            Panel::Floor,
            Panel::South,
            Panel::North,
            Panel::West,
            Panel::East,
            Panel::Ceiling,
        ];
        chart
            .draw_series(PANELS.iter().map(|&p| {
                let [a, b] = self.panel_rect(p);
                Rectangle::new(
                    [(a[0], a[1]), (b[0], b[1])],
                    RGBColor(235, 235, 235).filled(),
                )
            }))
            .map_err(failed)?;
        chart
            .draw_series(self.order.iter().map(|&i| {
                let p = &self.input.patches[i];
                let corners: Vec<(f64, f64)> = p
                    .vertices
                    .iter()
                    .map(|&v| {
                        let [u, w] = self.project(self.panels[i], v);
                        (u, w)
                    })
                    .collect();
                Polygon::new(corners, rgb(self.scale.colour(p.value)).filled())
            }))
            .map_err(failed)?;
        chart
            .draw_series(PANELS.iter().map(|&p| {
                let [a, b] = self.panel_rect(p);
                Rectangle::new([(a[0], a[1]), (b[0], b[1])], BLACK.stroke_width(1))
            }))
            .map_err(failed)?;
        let frame = Frame::of(&chart, xr, yr);
        let (ox, oy) = root.get_base_pixel();
        // Labels beside the panels, never over a patch: the wall y = lowest under its panel,
        // the others above theirs (the floor's is the caption's).
        for p in PANELS {
            let [a, b] = self.panel_rect(p);
            let mid = (a[0] + b[0]) / 2.0;
            let (c, r, dy) = match p {
                Panel::Floor => continue,
                Panel::South => {
                    let (c, r) = chart.backend_coord(&(mid, a[1]));
                    (c, r, 12)
                }
                _ => {
                    let (c, r) = chart.backend_coord(&(mid, b[1]));
                    (c, r, -12)
                }
            };
            let at = (c - ox, r - oy + dy);
            root.draw(&Text::new(
                self.panel_label(p),
                at,
                draw::text(13).pos(Pos::new(HPos::Center, VPos::Center)),
            ))
            .map_err(failed)?;
        }
        // A 1 m scale bar in the free corner below the wall at the lowest x.
        let (_, d, hgt) = self.sides();
        let _ = d;
        let (s0, s1) = (
            chart.backend_coord(&(-hgt * 0.9, -hgt * 0.5)),
            chart.backend_coord(&(-hgt * 0.9 + 1.0, -hgt * 0.5)),
        );
        root.draw(&PathElement::new(
            vec![(s0.0 - ox, s0.1 - oy), (s1.0 - ox, s1.1 - oy)],
            BLACK.stroke_width(3),
        ))
        .map_err(failed)?;
        root.draw(&Text::new(
            "1 m".to_owned(),
            (s0.0 - ox, s0.1 - oy + 6),
            draw::text(13),
        ))
        .map_err(failed)?;
        let (_, rows) = chart.plotting_area().get_pixel_range();
        let (_, base) = right.get_base_pixel();
        let bar = (rows.end - rows.start).min(360);
        draw::colour_bar(
            &right,
            &self.scale,
            rows.start - base + 20,
            bar,
            self.extras(),
        )?;
        draw::lines(&foot, &self.caption(), (10, 4), 14, Self::LINE as i32)?;
        Ok(frame)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The fold, by hand for a 6 × 4 × 2.8 m box: the floor's corners stay, a point 1 m up
    /// the wall y = 0 lies 1 m below the floor's edge, one 1 m up the wall x = 6 m lies 1 m
    /// beyond the floor's right edge, and the ceiling's corner above (6, 0) lies where the
    /// wall x = 6 m ends, at x = 6 + 2.8.
    #[test]
    fn the_net_folds_the_walls_out() {
        let quad = |v: [[f64; 3]; 4], n: [f64; 3]| NetPatch {
            vertices: v.to_vec(),
            normal: n,
            value: Some(1.0),
            emits: false,
        };
        let input = NetInput {
            title: String::new(),
            notes: Vec::new(),
            unit: "lux",
            quantity: "illuminance E",
            patches: vec![
                quad(
                    [
                        [0.0, 0.0, 0.0],
                        [6.0, 0.0, 0.0],
                        [6.0, 4.0, 0.0],
                        [0.0, 4.0, 0.0],
                    ],
                    [0.0, 0.0, 1.0],
                ),
                quad(
                    [
                        [0.0, 0.0, 2.8],
                        [0.0, 4.0, 2.8],
                        [6.0, 4.0, 2.8],
                        [6.0, 0.0, 2.8],
                    ],
                    [0.0, 0.0, -1.0],
                ),
            ],
        };
        let net = Net::new(input);
        assert_eq!(net.project(Panel::Floor, [6.0, 4.0, 0.0]), [6.0, 4.0]);
        assert_eq!(net.project(Panel::South, [2.0, 0.0, 1.0]), [2.0, -1.0]);
        assert_eq!(net.project(Panel::East, [6.0, 3.0, 1.0]), [7.0, 3.0]);
        assert_eq!(net.project(Panel::North, [2.0, 4.0, 1.0]), [2.0, 5.0]);
        assert_eq!(net.project(Panel::West, [0.0, 3.0, 1.0]), [-1.0, 3.0]);
        let c = net.project(Panel::Ceiling, [6.0, 0.0, 2.8]);
        assert!((c[0] - 8.8).abs() < 1e-12 && c[1] == 0.0);
        assert_eq!(Panel::of([0.0, 0.0, 1.0]), Panel::Floor);
        assert_eq!(Panel::of([0.0, 0.6, -0.8]), Panel::Ceiling);
        assert_eq!(Panel::of([-0.9, 0.1, 0.1]), Panel::East);
    }
}
