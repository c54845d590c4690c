//! The report of `eigenrad sky` as text.

use std::fmt::Write as _;

use super::SkyReport;

/// The report as text: one quantity a line, each with its unit.
pub fn format_sky(r: &SkyReport) -> String {
    let mut s = String::new();
    let _ = writeln!(s, "time                         {}", r.time);
    let _ = writeln!(
        s,
        "site                         {:.4}° N, {:.4}° E, {:.1} m; scene +y at {:.1}° from true north",
        r.site[0], r.site[1], r.site[2], r.north_deg
    );
    let _ = writeln!(
        s,
        "sun                          altitude {:.3}°, azimuth {:.3}° (clockwise from north), zenith {:.3}°",
        r.sun.altitude, r.sun.azimuth, r.sun.zenith
    );
    let d = r.sun_direction_room;
    let _ = writeln!(
        s,
        "sun direction (scene axes)   ({:.4}, {:.4}, {:.4})",
        d[0], d[1], d[2]
    );
    if r.sun_below_horizon {
        let _ = writeln!(
            s,
            "sun below the horizon        no direct light; the sky's shape with the sun on the horizon at its azimuth"
        );
    }
    let _ = writeln!(s, "sky                          {}", r.model);
    if let Some(p) = &r.perez {
        let _ = writeln!(
            s,
            "clearness ε, brightness Δ    {:.4}, {:.4}",
            p.clearness, p.brightness
        );
        let c = p.coefficients;
        let _ = writeln!(
            s,
            "Perez a, b, c, d, e          {:.4}, {:.4}, {:.4}, {:.4}, {:.4}",
            c[0], c[1], c[2], c[3], c[4]
        );
        let _ = writeln!(
            s,
            "efficacy                     diffuse {:.2} lm/W, direct {:.2} lm/W",
            p.diffuse_efficacy_lm_w, p.direct_efficacy_lm_w
        );
        let _ = writeln!(
            s,
            "irradiance                   diffuse horizontal {:.1} W/m², direct normal {:.1} W/m²",
            p.diffuse_horizontal_w_m2, p.direct_normal_w_m2
        );
    }
    let _ = writeln!(
        s,
        "zenith luminance             {:.1} cd/m²",
        r.zenith_luminance_cd_m2
    );
    let _ = writeln!(
        s,
        "diffuse horizontal           {:.1} lux",
        r.diffuse_horizontal_lux
    );
    let _ = writeln!(
        s,
        "direct                       {:.1} lux normal, {:.1} lux horizontal",
        r.direct_normal_lux, r.direct_horizontal_lux
    );
    let _ = writeln!(
        s,
        "global horizontal            {:.1} lux",
        r.global_horizontal_lux
    );
    let rel = if r.diffuse_horizontal_lux > 0.0 {
        100.0 * (r.patch_diffuse_horizontal_lux / r.diffuse_horizontal_lux - 1.0)
    } else {
        0.0
    };
    let _ = writeln!(
        s,
        "{:<28} {} patches: diffuse horizontal {:.1} lux from centre luminances ({rel:+.2} %)",
        r.patch_set,
        r.patches.len(),
        r.patch_diffuse_horizontal_lux
    );
    for note in &r.notes {
        let _ = writeln!(s, "note                         {note}");
    }
    s
}
