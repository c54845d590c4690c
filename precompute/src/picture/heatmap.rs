//! A year hour by hour as the annual tools draw it (DIVA's, Honeybee's and Ladybug's hourly
//! plot, DAYSIM's temporal map): a column of 24 cells a day, one cell an hour, each in the
//! colour of the hour's value on the pictures' false-colour scale ([`Scale`]), the days
//! along x with the months marked, the hours of the day up y, a colour bar in the value's
//! unit.
//!
//! The drawing takes plain numbers (a value an hour from a first date): what they are (a
//! controller's power, a zone's daylight) is the caller's to say in the title and notes.
//! Cells are whole pixels, the same number for every day and every hour, so each cell is one
//! flat colour that reads back to its value within half a bin ([`Scale::value_of`]).

use chrono::{Datelike, Duration, NaiveDate};
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::colour::{Rgb, Scale};
use super::draw::{self, failed, format_value, rgb, Extras, Format, Frame};

/// Hours of a day: the heat map's rows, and the values of one day.
pub const HOURS: usize = 24;

/// What a heat map shows: a value an hour, 24 a day, from `first_day`.
#[derive(Clone, Debug)]
pub struct HeatMapInput {
    /// First line: what is drawn, of what.
    pub title: String,
    /// The quantity's name, for the caption (`power`, `daylight on work_plane`).
    pub quantity: String,
    /// Unit of the values, under the colour bar: `W`, `lux`.
    pub unit: &'static str,
    /// The date of the first day, local standard time: sets the months along x.
    pub first_day: NaiveDate,
    /// The values, hour by hour: `values[24 d + h]` is the hour from `h`:00 to `h + 1`:00 of
    /// the day `d` days after `first_day`. Not a number where an hour has no value (a record
    /// missing from the weather file), drawn grey; a last day shorter than 24 hours is
    /// completed with no value.
    pub values: Vec<f64>,
    /// Further caption lines under the figures (the weather file, the strategy, the year's
    /// sum).
    pub notes: Vec<String>,
}

/// A heat map ready to draw: its input and its colour scale.
#[derive(Clone, Debug)]
pub struct HeatMap {
    /// What it shows.
    pub input: HeatMapInput,
    /// The value-to-colour map, over the values in round numbers.
    pub scale: Scale,
}

/// The plot's width aimed at, pixels: three a day for a year of 365 days.
const WIDTH: f64 = 1095.0;
/// Pixels an hour: the plot is 24 × 12 = 288 pixels high.
const ROW: i32 = 12;
/// The months' abbreviations, January first.
const MONTHS: [&str; 12] = [
    "Jan", "Feb", "Mar", "Apr", "May", "Jun", "Jul", "Aug", "Sep", "Oct", "Nov", "Dec",
];

impl HeatMap {
    /// The heat map of `input`: the scale spans its values (those that are numbers).
    pub fn new(input: HeatMapInput) -> HeatMap {
        let (lo, hi) = input
            .values
            .iter()
            .filter(|v| v.is_finite())
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        let (lo, hi) = if lo <= hi { (lo, hi) } else { (0.0, 0.0) };
        let scale = Scale::around(lo, hi, input.unit);
        HeatMap { input, scale }
    }

    /// The heat map as the bytes of a `format` file.
    pub fn file(&self, format: Format) -> Result<Vec<u8>, String> {
        match format {
            Format::Png => self.png().map(|(b, _)| b),
            Format::Svg => self.svg().map(|(s, _)| s.into_bytes()),
        }
    }

    /// The heat map as an SVG document, and where its days and hours lie in its pixels: the
    /// frame's `x` is days after the first day's midnight, its `y` hours of the day.
    pub fn svg(&self) -> Result<(String, Frame), String> {
        draw::svg(self.size(), |root| self.draw(root))
    }

    /// The heat map as PNG bytes, and where its days and hours lie in its pixels (as
    /// [`HeatMap::svg`]).
    pub fn png(&self) -> Result<(Vec<u8>, Frame), String> {
        draw::png(self.size(), |root| self.draw(root))
    }

    /// Days drawn: every day with a value, the last one completed.
    pub fn days(&self) -> usize {
        self.input.values.len().div_ceil(HOURS).max(1)
    }

    /// The value of hour `h` of day `d`; not a number where there is none.
    fn value(&self, d: usize, h: usize) -> f64 {
        self.input
            .values
            .get(d * HOURS + h)
            .copied()
            .unwrap_or(f64::NAN)
    }

    /// Pixels a day: the same for every day, about [`WIDTH`] for the whole span, at least 1.
    fn day_width(&self) -> i32 {
        (WIDTH / self.days() as f64).round().max(1.0) as i32
    }

    /// The plot's size in pixels.
    fn plot_size(&self) -> (i32, i32) {
        (self.days() as i32 * self.day_width(), HOURS as i32 * ROW)
    }

    const TITLE: i32 = 40;
    const LEFT: i32 = 70;
    const RIGHT: i32 = 15;
    const BAR: i32 = 130;
    const BELOW: i32 = 52;
    const LINE: i32 = 20;

    /// The plot's top left pixel.
    fn origin() -> (i32, i32) {
        (Self::LEFT, Self::TITLE + 10)
    }

    fn last_day(&self) -> NaiveDate {
        self.input.first_day + Duration::days(self.days() as i64 - 1)
    }

    fn caption(&self) -> Vec<String> {
        let i = &self.input;
        let u = i.unit;
        let finite: Vec<f64> = i.values.iter().copied().filter(|v| v.is_finite()).collect();
        let mut lines = vec![format!(
            "each column a day ({} to {}), each row an hour of local standard time (00:00 at the bottom), in the colour of its {} ({u})",
            i.first_day,
            self.last_day(),
            i.quantity
        )];
        if finite.is_empty() {
            lines.push("no hour has a value".into());
        } else {
            let fmt = |v: f64| format_value(v, self.scale.step / 100.0);
            let (lo, hi) = finite
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                    (a.min(v), b.max(v))
                });
            let mean = finite.iter().sum::<f64>() / finite.len() as f64;
            let missing = self.days() * HOURS - finite.len();
            // The days with a grey hour, named when they are few (the 29 February a year of
            // 365 records lacks when its dates are placed in a leap year).
            let grey_days: Vec<String> = (0..self.days())
                .filter(|&d| (0..HOURS).any(|h| !self.value(d, h).is_finite()))
                .map(|d| (i.first_day + Duration::days(d as i64)).to_string())
                .collect();
            let grey = match (missing, grey_days.len()) {
                (0, _) => String::new(),
                (_, 1..=3) => format!(
                    "; grey: {missing} hours without a value ({})",
                    grey_days.join(", ")
                ),
                _ => format!("; grey: {missing} hours without a value"),
            };
            lines.push(format!(
                "min {} {u}   mean {} {u}   max {} {u}   over {} hours{grey}",
                fmt(lo),
                fmt(mean),
                fmt(hi),
                finite.len()
            ));
        }
        lines.extend(i.notes.iter().cloned());
        let width = Self::LEFT + self.plot_size().0 + Self::RIGHT + Self::BAR - 20;
        draw::wrap(&lines, width as u32, 14)
    }

    fn size(&self) -> (u32, u32) {
        let (w, h) = self.plot_size();
        (
            (Self::LEFT + w + Self::RIGHT + Self::BAR) as u32,
            (Self::TITLE + 10 + h + Self::BELOW + Self::LINE * self.caption().len() as i32 + 10)
                as u32,
        )
    }

    /// The cells of day `d`: runs of hours of one colour, `(first hour, hours, colour)`.
    fn runs(&self, d: usize) -> Vec<(usize, usize, Rgb)> {
        let mut runs: Vec<(usize, usize, Rgb)> = Vec::new();
        for h in 0..HOURS {
            let colour = self.scale.colour(Some(self.value(d, h)));
            match runs.last_mut() {
                Some((_, n, c)) if *c == colour => *n += 1,
                _ => runs.push((h, 1, colour)),
            }
        }
        runs
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, plotters::coord::Shift>,
    ) -> Result<Frame, String> {
        let i = &self.input;
        let (w, h) = self.plot_size();
        let (x0, top) = Self::origin();
        let bottom = top + h;
        let dw = self.day_width();
        root.fill(&WHITE).map_err(failed)?;
        draw::lines(root, std::slice::from_ref(&i.title), (10, 12), 18, 0)?;
        // The cells: whole pixels, hour 0 at the bottom; runs of one colour as one rectangle.
        let mut extras = Extras::default();
        for d in 0..self.days() {
            let x = x0 + d as i32 * dw;
            for (first, n, colour) in self.runs(d) {
                extras.no_value |= colour == super::colour::NO_VALUE;
                let (lo, hi) = (first as i32, (first + n) as i32);
                root.draw(&Rectangle::new(
                    [(x, bottom - hi * ROW), (x + dw, bottom - lo * ROW)],
                    rgb(colour).filled(),
                ))
                .map_err(failed)?;
            }
        }
        // The frame, just outside the cells.
        root.draw(&Rectangle::new(
            [(x0 - 1, top - 1), (x0 + w, bottom)],
            BLACK.stroke_width(1),
        ))
        .map_err(failed)?;
        // Hours up y, every three.
        for hour in (0..=HOURS as i32).step_by(3) {
            let y = (bottom - hour * ROW).max(top - 1);
            root.draw(&PathElement::new(
                vec![(x0 - 6, y), (x0 - 1, y)],
                BLACK.stroke_width(1),
            ))
            .map_err(failed)?;
            root.draw(&Text::new(
                format!("{hour:02}:00"),
                (x0 - 9, y),
                draw::text(13).pos(Pos::new(HPos::Right, VPos::Center)),
            ))
            .map_err(failed)?;
        }
        root.draw(&Text::new(
            "hour of the day".to_owned(),
            (6, (top + bottom) / 2),
            draw::text(14)
                .transform(FontTransform::Rotate270)
                .pos(Pos::new(HPos::Center, VPos::Top)),
        ))
        .map_err(failed)?;
        // Months along x: a tick where each begins, its name in the middle of its days.
        let first = i.first_day;
        let days = self.days();
        let mut starts: Vec<usize> = (0..days)
            .filter(|&d| d == 0 || (first + Duration::days(d as i64)).day() == 1)
            .collect();
        starts.push(days);
        let label_width = draw::char_width(13) * 3.0 + 4.0;
        for pair in starts.windows(2) {
            let (a, b) = (pair[0], pair[1]);
            let xa = x0 + a as i32 * dw;
            root.draw(&PathElement::new(
                vec![(xa.max(x0 - 1), bottom + 1), (xa.max(x0 - 1), bottom + 7)],
                BLACK.stroke_width(1),
            ))
            .map_err(failed)?;
            if f64::from((b - a) as i32 * dw) >= label_width {
                let month = (first + Duration::days(a as i64)).month0() as usize;
                root.draw(&Text::new(
                    MONTHS[month].to_owned(),
                    (x0 + ((a + b) as i32 * dw) / 2, bottom + 9),
                    draw::text(13).pos(Pos::new(HPos::Center, VPos::Top)),
                ))
                .map_err(failed)?;
            }
        }
        root.draw(&PathElement::new(
            vec![(x0 + w, bottom + 1), (x0 + w, bottom + 7)],
            BLACK.stroke_width(1),
        ))
        .map_err(failed)?;
        let last = self.last_day();
        let along = if last.year() == first.year() {
            format!(
                "day of the year ({} to {})",
                first.ordinal(),
                last.ordinal()
            )
        } else {
            "day".to_owned()
        };
        root.draw(&Text::new(
            along,
            (x0 + w / 2, bottom + 28),
            draw::text(14).pos(Pos::new(HPos::Center, VPos::Top)),
        ))
        .map_err(failed)?;
        // The colour bar beside the plot, as tall as it.
        let (_, right) = root.split_horizontally((x0 + w + Self::RIGHT) as u32);
        draw::colour_bar(&right, &self.scale, top, h, extras)?;
        draw::lines(
            root,
            &self.caption(),
            (10, bottom + Self::BELOW + 4),
            14,
            Self::LINE,
        )?;
        Ok(Frame::new([
            ([0.0, 0.0], [x0, bottom]),
            ([days as f64, HOURS as f64], [x0 + w, top]),
        ]))
    }
}

#[cfg(test)]
mod tests {
    use super::super::colour::NO_VALUE;
    use super::*;

    /// A year of `f(day, hour)` from 1 January 2026.
    fn year(f: impl Fn(usize, usize) -> f64, days: usize) -> HeatMap {
        HeatMap::new(HeatMapInput {
            title: "A test year: power of the model strategy".into(),
            quantity: "power".into(),
            unit: "W",
            first_day: NaiveDate::from_ymd_opt(2026, 1, 1).unwrap(),
            values: (0..days * HOURS).map(|k| f(k / HOURS, k % HOURS)).collect(),
            notes: vec!["a note".into()],
        })
    }

    /// The PNG's width, height and RGB pixels.
    fn decode(bytes: &[u8]) -> (u32, u32, Vec<u8>) {
        let decoder = png::Decoder::new(std::io::Cursor::new(bytes));
        let mut reader = decoder.read_info().unwrap();
        let mut buf = vec![0; reader.output_buffer_size().unwrap()];
        let info = reader.next_frame(&mut buf).unwrap();
        assert_eq!(info.color_type, png::ColorType::Rgb);
        buf.truncate(info.buffer_size());
        (info.width, info.height, buf)
    }

    fn pixel(pixels: &[u8], width: u32, (c, r): (i32, i32)) -> Rgb {
        let k = (r as usize * width as usize + c as usize) * 3;
        [pixels[k], pixels[k + 1], pixels[k + 2]]
    }

    /// A year of 365 days: three pixels a day (1095), twelve an hour (288), the plot at the
    /// frame's corners; the picture as wide as the margins, the plot and the colour bar, as
    /// high as the title, the plot, the axis and the caption's lines.
    #[test]
    fn a_year_is_three_pixels_a_day_and_twelve_an_hour() {
        let map = year(|d, h| (d + h) as f64, 365);
        assert_eq!(map.days(), 365);
        let (bytes, frame) = map.png().unwrap();
        let (w, h, _) = decode(&bytes);
        let caption = map.caption().len() as u32;
        assert_eq!(w, 70 + 1095 + 15 + 130);
        assert_eq!(h, 40 + 10 + 288 + 52 + 20 * caption + 10);
        assert_eq!(frame.pixel(0.0, 0.0), (70, 50 + 288));
        assert_eq!(frame.pixel(365.0, 24.0), (70 + 1095, 50));
        // A leap year's 366 days: still three pixels a day.
        let leap = year(|_, _| 1.0, 366);
        assert_eq!(leap.plot_size(), (1098, 288));
        // Three days: a third of the width each.
        assert_eq!(year(|_, _| 1.0, 3).plot_size(), (1095, 288));
    }

    /// Every pixel of the plot of a constant field is the scale's colour of that value (the
    /// field sits mid-scale), and nothing else is drawn over the cells.
    #[test]
    fn a_constant_field_is_one_colour() {
        let map = year(|_, _| 240.0, 365);
        let colour = map.scale.colour(Some(240.0));
        assert!(map.scale.min < 240.0 && 240.0 < map.scale.max);
        let (bytes, frame) = map.png().unwrap();
        let (w, _, pixels) = decode(&bytes);
        let (left, bottom) = frame.pixel(0.0, 0.0);
        let (right, top) = frame.pixel(365.0, 24.0);
        for r in top..bottom {
            for c in left..right {
                assert_eq!(pixel(&pixels, w, (c, r)), colour, "pixel ({c}, {r})");
            }
        }
        // The frame just outside is black.
        assert_eq!(pixel(&pixels, w, (left - 1, (top + bottom) / 2)), [0, 0, 0]);
        assert_eq!(pixel(&pixels, w, (right, (top + bottom) / 2)), [0, 0, 0]);
    }

    /// Each cell's colour, read at its centre, maps back to its hour's value within half a
    /// colour bin: the hours run up from 00:00 at the bottom, the days along from the left,
    /// and a value missing from the input is grey.
    #[test]
    fn every_cell_reads_back_its_value() {
        // A value for every (day, hour) of a week, all different; hour 5 of day 2 missing.
        let f = |d: usize, h: usize| {
            if (d, h) == (2, 5) {
                f64::NAN
            } else {
                10.0 * d as f64 + h as f64 / 3.0
            }
        };
        let map = year(f, 7);
        let (bytes, frame) = map.png().unwrap();
        let (w, _, pixels) = decode(&bytes);
        let half = map.scale.bin_width() / 2.0;
        for d in 0..7 {
            for h in 0..HOURS {
                let at = frame.pixel(d as f64 + 0.5, h as f64 + 0.5);
                let rgb = pixel(&pixels, w, at);
                let v = f(d, h);
                if v.is_nan() {
                    assert_eq!(rgb, NO_VALUE);
                    continue;
                }
                let back = map.scale.value_of(rgb).unwrap();
                assert!(
                    (back - v).abs() <= half * (1.0 + 1e-12),
                    "{d} {h}: {back} {v}"
                );
            }
        }
        assert!(map
            .caption()
            .iter()
            .any(|l| l.contains("grey: 1 hours without a value (2026-01-03)")));
        // 30 hours: the second day's last 18 hours have no value.
        let short = HeatMap::new(HeatMapInput {
            values: (0..30).map(f64::from).collect(),
            ..map.input.clone()
        });
        assert_eq!(short.days(), 2);
        let (bytes, frame) = short.png().unwrap();
        let (w, _, pixels) = decode(&bytes);
        assert_eq!(pixel(&pixels, w, frame.pixel(1.5, 6.5)), NO_VALUE);
        assert_ne!(pixel(&pixels, w, frame.pixel(1.5, 5.5)), NO_VALUE);
    }

    /// The same input gives the same PNG and SVG bytes; the SVG carries the title, the unit
    /// under the colour bar, the quantity in the caption and the months.
    #[test]
    fn the_same_bytes_twice_and_the_svg_says_what_it_shows() {
        let a = year(|d, h| ((d * 7 + h * 13) % 50) as f64, 365);
        let b = year(|d, h| ((d * 7 + h * 13) % 50) as f64, 365);
        assert_eq!(a.png().unwrap().0, b.png().unwrap().0);
        let svg = a.svg().unwrap().0;
        assert_eq!(svg, b.svg().unwrap().0);
        assert_eq!(a.file(Format::Svg).unwrap(), svg.as_bytes());
        for text in [
            "A test year: power of the model strategy",
            "\nW\n",
            "in the colour of its power",
            "\nJan\n",
            "\nDec\n",
            "day of the year (1 to 365)",
            "a note",
        ] {
            assert!(svg.contains(text), "{text} not in the SVG");
        }
    }
}
