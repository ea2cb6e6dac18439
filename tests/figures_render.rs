//! Every figure SVG renders: the panels of `v2ref reproduce` (every figure
//! at quick effort, through the same writer) and the plan's SVG are parsed
//! by usvg and drawn by resvg, an SVG renderer independent of plotters,
//! which writes them. A malformed SVG, a panel drawn blank, a size other
//! than the one declared, or text that cannot be laid out fails; the
//! plan's texts (its ticks) are each drawn once.

use resvg::{tiny_skia, usvg};
use std::process::Command;
use v2ref_reproduction::cases::Effort;

/// Below this share of non-white pixels a panel counts as blank (a panel
/// has axes, grid, curves and text: several percent).
const MIN_INKED_SHARE: f64 = 0.005;

/// The width of every panel and of the plan, pixels (slides take them
/// side by side or one per slide at this width).
const WIDTH_PX: f32 = 900.0;

/// Font options with the system fonts, the generic `sans-serif` of the
/// figures mapped to one that exists (DejaVu Sans where present). Also
/// says whether any font was found: without one, text cannot be laid out
/// and only parsing and drawing are checked.
fn options() -> (usvg::Options<'static>, bool) {
    let mut opt = usvg::Options::default();
    let db = opt.fontdb_mut();
    db.load_system_fonts();
    let families: Vec<String> = db
        .faces()
        .flat_map(|f| f.families.iter().map(|(name, _)| name.clone()))
        .collect();
    let sans = families
        .iter()
        .find(|f| f.as_str() == "DejaVu Sans")
        .or_else(|| families.first())
        .cloned();
    if let Some(family) = &sans {
        db.set_sans_serif_family(family.clone());
    }
    (opt, sans.is_some())
}

/// The `width="…"`/`height="…"` the SVG's root element declares, pixels.
fn declared_size(svg: &str) -> Option<(f32, f32)> {
    let root = &svg[svg.find("<svg")?..];
    let root = &root[..root.find('>')?];
    let attribute = |name: &str| -> Option<f32> {
        let start = root.find(&format!(" {name}=\""))? + name.len() + 3;
        let len = root[start..].find('"')?;
        root[start..start + len].parse().ok()
    };
    Some((attribute("width")?, attribute("height")?))
}

/// The text nodes of a tree, and how many of them were laid out into
/// glyphs.
fn text_nodes(group: &usvg::Group) -> (usize, usize) {
    group.children().iter().fold((0, 0), |(all, laid), node| {
        let (a, l) = match node {
            usvg::Node::Text(text) => (
                1,
                usize::from(!text.layouted().is_empty() && text.bounding_box().width() > 0.0),
            ),
            usvg::Node::Group(g) => text_nodes(g),
            _ => (0, 0),
        };
        (all + a, laid + l)
    })
}

/// Parses and draws `svg`; an error says what is wrong with it.
fn check_svg(svg: &str, opt: &usvg::Options, fonts: bool) -> Result<(), String> {
    let tree = usvg::Tree::from_str(svg, opt).map_err(|e| format!("does not parse: {e}"))?;
    let (width, height) = declared_size(svg).ok_or("no declared width and height")?;
    let size = tree.size();
    if width != WIDTH_PX || (size.width(), size.height()) != (width, height) {
        return Err(format!(
            "drawn {}x{}, declared {width}x{height}, expected {WIDTH_PX} wide",
            size.width(),
            size.height()
        ));
    }
    let mut pixmap = tiny_skia::Pixmap::new(width as u32, height as u32).ok_or("empty size")?;
    resvg::render(&tree, tiny_skia::Transform::default(), &mut pixmap.as_mut());
    let inked = pixmap
        .pixels()
        .iter()
        .filter(|p| p.alpha() > 0 && (p.red(), p.green(), p.blue()) != (255, 255, 255))
        .count();
    let share = inked as f64 / (width * height) as f64;
    if share < MIN_INKED_SHARE {
        return Err(format!("blank: {share:.4} of the pixels inked"));
    }
    let written = svg.matches("<text").count();
    let (parsed, laid_out) = text_nodes(tree.root());
    if fonts && (parsed != written || laid_out != written) {
        return Err(format!(
            "{written} texts written, {parsed} parsed, {laid_out} laid out"
        ));
    }
    Ok(())
}

#[test]
#[ignore = "slow tier: every figure panel rendered (6 s)"]
fn every_figure_panel_renders() {
    let (opt, fonts) = options();
    if !fonts {
        eprintln!("no system font: text layout not checked, parsing and drawing only");
    }
    let figures = v2ref_reproduction::figures::all(Effort::Quick).unwrap();
    let mut panels = 0;
    for fig in &figures {
        for table in &fig.tables {
            let svg = v2ref_reproduction::plot::table_svg(fig, table).unwrap();
            if let Err(why) = check_svg(&svg, &opt, fonts) {
                panic!("{}.svg: {why}", table.name);
            }
            panels += 1;
        }
    }
    // Figs. 0 to 5: 1 + 2 + 2 + 4 + 4 + 2 panels.
    assert_eq!(panels, 15);
}

#[test]
fn plan_svg_renders() {
    let (opt, fonts) = options();
    let dir = tempfile::tempdir().unwrap();
    let svg = dir.path().join("plan.svg");
    let out = Command::new(env!("CARGO_BIN_EXE_v2ref"))
        .args([
            "plan",
            "--source",
            "ud",
            "--diameter-mas",
            "2",
            "--baseline-m",
            "100",
            "--fringe-hz",
            "100",
            "--fringe-hz",
            "1000",
            "--stroke-um",
            "32",
            "--scans",
            "300",
            "--svg",
        ])
        .arg(&svg)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&svg).unwrap();
    if let Err(why) = check_svg(&text, &opt, fonts) {
        panic!("plan.svg: {why}");
    }
    // Each text once: an axis ticked 1 to 9 in a decade had its next
    // decade's tick drawn twice, over itself (here "1000" on the frequency
    // axis, 83 to 1200 Hz, whatever the plan's numbers; and "1e-2").
    let mut texts = svg_texts(&text);
    assert!(texts.contains(&"1000"), "{texts:?}");
    texts.sort_unstable();
    let twice: Vec<_> = texts.windows(2).filter(|w| w[0] == w[1]).collect();
    assert!(twice.is_empty(), "plan.svg draws a text twice: {twice:?}");
}

/// The content of each `<text>` element of an SVG written by plotters,
/// trimmed.
fn svg_texts(svg: &str) -> Vec<&str> {
    svg.split("<text")
        .skip(1)
        .filter_map(|s| Some(s[s.find('>')? + 1..s.find("</text>")?].trim()))
        .collect()
}

/// The checks can fail: a truncated panel does not parse, a blank one is
/// blank, a wrong declared size is caught, and text in a font family that
/// does not exist (with no fallback) is not laid out.
#[test]
fn broken_svgs_fail() {
    let (opt, fonts) = options();
    let figure = v2ref_reproduction::figures::all(Effort::Quick)
        .unwrap()
        .remove(0);
    let svg = v2ref_reproduction::plot::table_svg(&figure, &figure.tables[0]).unwrap();
    assert!(check_svg(&svg, &opt, fonts).is_ok());

    let truncated = &svg[..svg.len() / 2];
    assert!(check_svg(truncated, &opt, fonts).is_err(), "truncated");

    let blank = r#"<svg width="900" height="560" xmlns="http://www.w3.org/2000/svg"><rect width="900" height="560" fill="white"/></svg>"#;
    let why = check_svg(blank, &opt, fonts).unwrap_err();
    assert!(why.starts_with("blank"), "{why}");

    let resized = svg.replacen("width=\"900\"", "width=\"901\"", 1);
    assert!(check_svg(&resized, &opt, fonts).is_err(), "declared size");

    if fonts {
        let mut no_fallback = usvg::Options::default();
        no_fallback.fontdb_mut().load_system_fonts();
        no_fallback.font_family = "no such family".into();
        let unknown = svg.replace("sans-serif", "no such family");
        let why = check_svg(&unknown, &no_fallback, fonts).unwrap_err();
        assert!(why.contains("laid out"), "{why}");
    }
}
