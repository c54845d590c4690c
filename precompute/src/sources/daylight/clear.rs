//! The clear windows' light alone on some of a scene's patches: what passes straight through
//! a room's windows onto the room beyond an exact port's opening (the scene both rooms), where
//! a diffusing window's light is its patches' emission.

use eigenrad_runtime::sky::patches::SkyPatches;

use super::{glazing, sky, sun, DaylightOptions, SkyResponse};
use crate::formfactor::Occluders;
use crate::geometry::Vec3;
use crate::scene::Scene;
use crate::sources::ChannelLight;

/// [`sky_response`](super::sky_response) from the clear windows alone, on the patches `receiving` marks (indices
/// into [`Scene::patches`]; the others read 0) and at every output: the light that passes
/// straight through the windows, where the diffusing windows' is their patches' emission.
/// An exact port's merge lights the room beyond the opening with it (the scene both rooms).
///
/// # Panics
///
/// As [`sky_response`](super::sky_response).
pub fn clear_sky_on(
    scene: &Scene,
    occluders: &Occluders,
    patches: SkyPatches,
    opts: &DaylightOptions,
    receiving: &[bool],
) -> SkyResponse {
    sky::response_on(
        scene,
        occluders,
        patches,
        opts,
        &glazing(scene),
        Some(receiving),
    )
}

/// [`sun_light`](super::sun_light) from the clear windows alone, on the patches `receiving` marks and at every
/// output, as [`clear_sky_on`].
///
/// # Panics
///
/// As [`sun_light`](super::sun_light).
pub fn clear_sun_on(
    scene: &Scene,
    occluders: &Occluders,
    direction: Vec3,
    opts: &DaylightOptions,
    receiving: &[bool],
) -> ChannelLight {
    sun::light_on(
        scene,
        occluders,
        direction,
        opts,
        &glazing(scene),
        Some(receiving),
    )
}
