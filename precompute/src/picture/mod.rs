//! False-colour pictures: the plan of a work plane with isolux lines ([`plan`]) and the room's
//! surfaces unfolded ([`net`]) of `eigenrad render`, and a year hour by hour as a day × hour
//! heat map ([`heatmap`]) of `eigenrad simulate`, as PNG or SVG, through plotters.
//!
//! One value-to-colour map serves every picture, its colour bar and the tests
//! ([`colour::Scale`]); isolux lines come from marching squares on the grid ([`contour`]).
//! The bytes depend only on what is drawn: one embedded font, no system fonts, no dates.

pub mod colour;
pub mod contour;
mod draw;
pub mod heatmap;
pub mod net;
pub mod plan;

pub use colour::Scale;
pub use draw::{format_value, register_font, Format, Frame};
pub use heatmap::{HeatMap, HeatMapInput};
pub use net::{Net, NetInput, NetPatch, Panel};
pub use plan::{Footprint, Plan, PlanGrid, PlanInput};
