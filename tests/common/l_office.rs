//! The L-shaped office of `examples/l-office/` as the importer tests use it: a coarse mesh and
//! a 2 m work-plane grid, its photometry found from anywhere, and its room replaceable by an
//! imported one.

use std::path::PathBuf;

/// The repository's root.
pub fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The L-shaped office's scene at a coarse mesh (2 m) and a 2 m work-plane grid, its files
/// found from anywhere, with its `[[room]]` and window quads replaced by `room` when given.
pub fn scene(room: Option<&str>) -> String {
    let text = std::fs::read_to_string(root().join("examples/l-office/scene.toml")).unwrap();
    // Daylight is gathered through every window at each receiver: a 2 m grid keeps it cheap.
    let text = text
        .replace("max_edge = 0.6", "max_edge = 2.0")
        .replace(
            "max_edge = 2.0 }",
            "max_edge = 2.0, grid = { spacing = 2.0 } }",
        )
        .replace(
            "\"../photometry/",
            &format!("\"{}/examples/photometry/", root().display()),
        );
    match room {
        None => text,
        Some(room) => {
            let start = text.find("[[room]]").unwrap();
            let end = text.find("# Two 0.4 m square columns").unwrap();
            format!("{}{room}\n{}", &text[..start], &text[end..])
        }
    }
}
