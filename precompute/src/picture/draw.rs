//! What the pictures share: the font, the two file formats, the colour bar, text in boxes,
//! and the frame that maps a drawing's coordinates (metres, or days and hours) to pixels.

use std::sync::Once;

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::colour::{Rgb, Scale, ABOVE, LEVELS, NO_VALUE};

/// The one font family of every picture. Text is measured (and, in PNG, drawn) with Hack
/// Regular, embedded in the program; an SVG names the family and leaves the face to its
/// viewer.
pub const FONT: &str = "sans-serif";

/// Registers the embedded font under `FONT` (once per process). Every plotters drawing of
/// the precompute (the pictures, `eigenrad verify`'s curves) needs it before any text.
pub fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        // The embedded font is valid (a test draws text with it): nothing to report.
        let _ = plotters::style::register_font(
            FONT,
            FontStyle::Normal,
            epaint_default_fonts::HACK_REGULAR,
        );
    });
}

/// The file format of a picture, from its file name's extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// PNG, 8-bit RGB.
    Png,
    /// SVG 1.1 text.
    Svg,
}

impl Format {
    /// The format a file name asks for (`.png` or `.svg`, any case), `None` otherwise.
    pub fn of(path: &std::path::Path) -> Option<Format> {
        let ext = path.extension()?.to_str()?.to_ascii_lowercase();
        match ext.as_str() {
            "png" => Some(Format::Png),
            "svg" => Some(Format::Svg),
            _ => None,
        }
    }
}

/// Where the coordinates of a picture's drawing lie in its pixels: `pixel` maps a point of
/// the plan or of the surfaces' unfolded net (m), or a heat map's (days, hours), to the pixel
/// (column, row) it is drawn at.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    /// Two points, m, and the pixels they are drawn at.
    corners: [([f64; 2], [i32; 2]); 2],
}

impl Frame {
    /// The frame that draws each of two points (x, y) at its pixel (column, row).
    pub(super) fn new(corners: [([f64; 2], [i32; 2]); 2]) -> Frame {
        Frame { corners }
    }

    /// The pixel (column, row from the top) where the point `(x, y)` (m, or days and hours)
    /// is drawn.
    pub fn pixel(&self, x: f64, y: f64) -> (i32, i32) {
        let [(a, pa), (b, pb)] = self.corners;
        let map = |v: f64, v0: f64, v1: f64, p0: i32, p1: i32| {
            (f64::from(p0) + (v - v0) / (v1 - v0) * f64::from(p1 - p0)).round() as i32
        };
        (
            map(x, a[0], b[0], pa[0], pb[0]),
            map(y, a[1], b[1], pa[1], pb[1]),
        )
    }

    /// The point (m, or days and hours) drawn at pixel `(column, row)`.
    pub fn position(&self, column: i32, row: i32) -> [f64; 2] {
        let [(a, pa), (b, pb)] = self.corners;
        let unmap = |p: i32, p0: i32, p1: i32, v0: f64, v1: f64| {
            v0 + f64::from(p - p0) / f64::from(p1 - p0) * (v1 - v0)
        };
        [
            unmap(column, pa[0], pb[0], a[0], b[0]),
            unmap(row, pa[1], pb[1], a[1], b[1]),
        ]
    }

    /// The frame of a chart over `[x0, x1] × [y0, y1]` m.
    pub(super) fn of<DB: DrawingBackend>(
        chart: &ChartContext<'_, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
        [x0, x1]: [f64; 2],
        [y0, y1]: [f64; 2],
    ) -> Frame {
        let p = |x, y| {
            let (c, r) = chart.backend_coord(&(x, y));
            ([x, y], [c, r])
        };
        Frame {
            corners: [p(x0, y0), p(x1, y1)],
        }
    }
}

/// A drawing failure, as text (plotters' errors carry the backend's type).
pub(super) fn failed<E: std::fmt::Display>(e: E) -> String {
    e.to_string()
}

/// A text style of the picture's font, black, `size` pixels.
pub(super) fn text(size: u32) -> TextStyle<'static> {
    (FONT, size).into_font().color(&BLACK)
}

/// An sRGB colour for plotters.
pub(super) fn rgb(c: Rgb) -> RGBColor {
    RGBColor(c[0], c[1], c[2])
}

/// `value` with as many decimals as `step` needs (500, 2.5, 0.05).
pub fn format_value(value: f64, step: f64) -> String {
    let decimals = (0..6)
        .find(|&d| {
            let scaled = step * 10f64.powi(d);
            (scaled - scaled.round()).abs() <= 1e-6 * scaled.abs().max(1.0)
        })
        .unwrap_or(6);
    format!("{value:.*}", decimals as usize)
}

/// Draws `label` centred at `at` (pixels of `area`) on a white box.
pub(super) fn boxed_label<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    label: &str,
    at: (i32, i32),
    size: u32,
) -> Result<(), String> {
    let style = text(size).pos(Pos::new(HPos::Center, VPos::Center));
    let (w, h) = area.estimate_text_size(label, &style).map_err(failed)?;
    let (w, h) = (w as i32 / 2 + 2, h as i32 / 2 + 1);
    area.draw(&Rectangle::new(
        [(at.0 - w, at.1 - h), (at.0 + w, at.1 + h)],
        WHITE.filled(),
    ))
    .map_err(failed)?;
    area.draw(&Text::new(label.to_owned(), at, style))
        .map_err(failed)
}

/// Pixels per character of the font at `size` pixels: Hack is monospaced, 0.6 em a glyph.
pub(super) fn char_width(size: u32) -> f64 {
    0.6 * f64::from(size)
}

/// `lines` broken at spaces into lines of at most `width` pixels of text `size` pixels high
/// (a word longer than that stays whole).
pub(super) fn wrap(lines: &[String], width: u32, size: u32) -> Vec<String> {
    let most = ((f64::from(width) / char_width(size)).floor() as usize).max(20);
    let mut out = Vec::new();
    for line in lines {
        let mut current = String::new();
        for word in line.split(' ') {
            let len = current.chars().count();
            if len > 0 && len + 1 + word.chars().count() > most {
                out.push(std::mem::take(&mut current));
                current.push_str("    ");
            } else if len > 0 {
                current.push(' ');
            }
            current.push_str(word);
        }
        out.push(current);
    }
    out
}

/// Lines of text from `(x, y)` down, `size` pixels, `gap` pixels apart.
pub(super) fn lines<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    lines: &[String],
    (x, y): (i32, i32),
    size: u32,
    gap: i32,
) -> Result<(), String> {
    for (k, line) in lines.iter().enumerate() {
        area.draw(&Text::new(
            line.clone(),
            (x, y + k as i32 * gap),
            text(size),
        ))
        .map_err(failed)?;
    }
    Ok(())
}

/// Which of the colours outside the scale a picture uses, for the colour bar's key.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Extras {
    /// Some value lies above the scale ([`ABOVE`]).
    pub above: bool,
    /// Some element has no value ([`NO_VALUE`]).
    pub no_value: bool,
}

/// The colour bar: the scale's [`LEVELS`] colours from `top` to `top + height` (pixels of
/// `area`, lowest value at the bottom), its round values labelled, the unit under it, and
/// boxes for the colours outside the scale that are used.
pub(super) fn colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    scale: &Scale,
    top: i32,
    height: i32,
    extras: Extras,
) -> Result<(), String> {
    let (x0, x1) = (12, 34);
    let bottom = top + height;
    let row = |t: f64| bottom - (t * f64::from(height)).round() as i32;
    for k in 0..LEVELS {
        let (lo, hi) = (k as f64 / LEVELS as f64, (k + 1) as f64 / LEVELS as f64);
        area.draw(&Rectangle::new(
            [(x0, row(hi)), (x1, row(lo))],
            rgb(Scale::bin_colour(k)).filled(),
        ))
        .map_err(failed)?;
    }
    area.draw(&Rectangle::new(
        [(x0, top), (x1, bottom)],
        BLACK.stroke_width(1),
    ))
    .map_err(failed)?;
    for t in scale.ticks() {
        let y = row((t - scale.min) / (scale.max - scale.min));
        area.draw(&PathElement::new(
            vec![(x1, y), (x1 + 5, y)],
            BLACK.stroke_width(1),
        ))
        .map_err(failed)?;
        area.draw(&Text::new(
            format_value(t, scale.step),
            (x1 + 8, y),
            text(13).pos(Pos::new(HPos::Left, VPos::Center)),
        ))
        .map_err(failed)?;
    }
    area.draw(&Text::new(
        scale.unit.to_owned(),
        (x0, bottom + 10),
        text(14),
    ))
    .map_err(failed)?;
    let mut y = bottom + 34;
    for (used, colour, label) in [
        (extras.above, ABOVE, "above the scale"),
        (extras.no_value, NO_VALUE, "no value"),
    ] {
        if !used {
            continue;
        }
        area.draw(&Rectangle::new(
            [(x0, y), (x1, y + 14)],
            rgb(colour).filled(),
        ))
        .map_err(failed)?;
        area.draw(&Rectangle::new(
            [(x0, y), (x1, y + 14)],
            BLACK.stroke_width(1),
        ))
        .map_err(failed)?;
        area.draw(&Text::new(
            label.to_owned(),
            (x1 + 8, y + 7),
            text(12).pos(Pos::new(HPos::Left, VPos::Center)),
        ))
        .map_err(failed)?;
        y += 22;
    }
    Ok(())
}

/// The plot's size in pixels for the drawn `range` (m): metres at one scale on both axes, the
/// largest that fits `max_plot` pixels and is at most `max_scale` pixels a metre, and at least
/// 40 pixels a side.
pub(super) fn plot_size(
    ([x0, x1], [y0, y1]): ([f64; 2], [f64; 2]),
    max_plot: (f64, f64),
    max_scale: f64,
) -> (u32, u32) {
    let s = (max_plot.0 / (x1 - x0))
        .min(max_plot.1 / (y1 - y0))
        .min(max_scale);
    (
        ((x1 - x0) * s).round().max(40.0) as u32,
        ((y1 - y0) * s).round().max(40.0) as u32,
    )
}

/// A picture drawn into an SVG document of `size` pixels.
pub(super) fn svg(
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<SVGBackend<'_>, Shift>) -> Result<Frame, String>,
) -> Result<(String, Frame), String> {
    register_font();
    let mut out = String::new();
    let frame = {
        let root = SVGBackend::with_string(&mut out, size).into_drawing_area();
        root.fill(&WHITE).map_err(failed)?;
        let frame = draw(&root)?;
        root.present().map_err(failed)?;
        frame
    };
    Ok((out, frame))
}

/// A picture drawn into an RGB buffer of `size` pixels and encoded as PNG (8-bit RGB, one
/// fixed filter and compression level, so the bytes depend on the pixels only).
pub(super) fn png(
    size: (u32, u32),
    draw: impl FnOnce(&DrawingArea<BitMapBackend<'_>, Shift>) -> Result<Frame, String>,
) -> Result<(Vec<u8>, Frame), String> {
    register_font();
    let mut pixels = vec![255u8; size.0 as usize * size.1 as usize * 3];
    let frame = {
        let root = BitMapBackend::with_buffer(&mut pixels, size).into_drawing_area();
        let frame = draw(&root)?;
        root.present().map_err(failed)?;
        frame
    };
    let mut out = Vec::new();
    {
        let mut encoder = png::Encoder::new(&mut out, size.0, size.1);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::High);
        encoder.set_filter(png::Filter::Paeth);
        let mut writer = encoder.write_header().map_err(failed)?;
        writer.write_image_data(&pixels).map_err(failed)?;
        writer.finish().map_err(failed)?;
    }
    Ok((out, frame))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_lines_wrap_at_spaces() {
        let lines = wrap(
            &["aaaa bbbb cccc dddd eeee ffff gggg".to_owned()],
            20 * 9,
            15,
        );
        assert_eq!(lines, vec!["aaaa bbbb cccc dddd", "    eeee ffff gggg"]);
        assert!(lines.iter().all(|l| l.chars().count() <= 20));
    }

    #[test]
    fn values_get_the_decimals_of_their_step() {
        assert_eq!(format_value(500.0, 100.0), "500");
        assert_eq!(format_value(12.5, 2.5), "12.5");
        assert_eq!(format_value(0.05, 0.01), "0.05");
        assert_eq!(format_value(3.0, 0.25), "3.00");
    }

    /// The embedded font draws: text turns pixels of a white PNG dark.
    #[test]
    fn the_font_draws_text() {
        let (bytes, _) = png((80, 30), |root| {
            root.fill(&WHITE).map_err(failed)?;
            root.draw(&Text::new("500 lx".to_owned(), (5, 5), text(16)))
                .map_err(failed)?;
            Ok(Frame {
                corners: [([0.0, 0.0], [0, 0]), ([1.0, 1.0], [1, 1])],
            })
        })
        .unwrap();
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        reader.next_frame(&mut buf).unwrap();
        let dark = buf.chunks(3).filter(|p| p.iter().all(|&c| c < 100)).count();
        assert!(dark > 20, "{dark} dark pixels");
    }
}
