//! Sensors and zones: where the results are read.

mod sensors;
mod work_plane;
mod zones;

pub(crate) use sensors::sensors;
pub(crate) use zones::zones;
