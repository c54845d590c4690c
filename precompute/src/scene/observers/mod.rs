//! Sensors and zones: where the results are read.

mod imported_grids;
mod sensors;
mod work_plane;
mod zones;

pub(crate) use imported_grids::imported_grids;
pub(crate) use sensors::sensors;
pub(crate) use zones::zones;
