//! Words for a panel: legend labels from column names, and the figure's
//! parameters as the subtitle.

/// A column name in words, with units: `v2_minus_vmono_12p5nm` becomes
/// "V2 - V mono, band 12.5 nm".
pub fn legend_label(name: &str) -> String {
    let (head, qualifier) = split_qualifier(name);
    let head = head.replace('_', " ");
    let words = match head.as_str() {
        "v1 minus vmono" => "V1 - V mono".to_owned(),
        "v2 minus vmono" => "V2 - V mono".to_owned(),
        "v2 calibrated minus vmono" => "V2 calibrated - V mono".to_owned(),
        "bias v1" => "bias of V1 (on V)".to_owned(),
        "bias v2" => "bias of V2 (on V)".to_owned(),
        "scatter v1" => "scatter of V1 (on V)".to_owned(),
        "scatter v2" => "scatter of V2 (on V)".to_owned(),
        "bias v1 dft" => "bias of V1, DFT".to_owned(),
        "bias v2 dft" => "bias of V2, DFT".to_owned(),
        "bias v1 convolution" => "bias of V1, convolution".to_owned(),
        "bias v2 convolution" => "bias of V2, convolution".to_owned(),
        "v2 numerical" => "V2, numerical integration".to_owned(),
        "v2 fresnel" => "V2, Fresnel integrals".to_owned(),
        "dev v2 flat" => "V2, flat band".to_owned(),
        "dev v2sq flat" => "V2 squared, flat band".to_owned(),
        "dev v2 smooth edges" => "V2, band with smooth edges".to_owned(),
        "dev riemann flat" => "V2, flat band, Riemann sum".to_owned(),
        "dev v2 index" => "V2, power-law band, index".to_owned(),
        other => other.to_owned(),
    };
    match qualifier {
        Some(q) if words.ends_with("index") => format!("{words} {q}"),
        Some(q) => format!("{words}, {}", describe_qualifier(&q)),
        None => words,
    }
}

/// Splits a trailing value such as `12p5nm`, `256um`, `1p5rad` or `-2`.
fn split_qualifier(name: &str) -> (String, Option<String>) {
    match name.rsplit_once('_') {
        Some((head, tail))
            if tail
                .chars()
                .next()
                .is_some_and(|c| c.is_ascii_digit() || c == '-') =>
        {
            (head.to_owned(), Some(tail.replace('p', ".")))
        }
        _ => (name.to_owned(), None),
    }
}

fn describe_qualifier(q: &str) -> String {
    let split = q.find(|c: char| c.is_ascii_alphabetic()).unwrap_or(q.len());
    let (value, unit) = q.split_at(split);
    match unit {
        "nm" => format!("bandwidth {value} nm"),
        "um" => format!("scan {value} µm"),
        "rad" => format!("dispersion {value} rad"),
        "" => value.to_owned(),
        u => format!("{value} {u}"),
    }
}

/// The figure's scalar parameters on one line, `name = value`, for the
/// subtitle.
pub(super) fn parameter_line(parameters: &serde_json::Value) -> String {
    let Some(map) = parameters.as_object() else {
        return String::new();
    };
    let items: Vec<String> = map
        .iter()
        .filter_map(|(k, v)| {
            let v = match v {
                serde_json::Value::Number(n) => n.to_string(),
                serde_json::Value::String(s) if s.len() <= 24 => s.clone(),
                serde_json::Value::Bool(b) => b.to_string(),
                serde_json::Value::Array(a) if a.len() <= 6 && a.iter().all(|x| x.is_number()) => a
                    .iter()
                    .map(|x| x.to_string())
                    .collect::<Vec<_>>()
                    .join("/"),
                _ => return None,
            };
            let units = [
                ("_um", "µm"),
                ("_nm", "nm"),
                ("_mas", "mas"),
                ("_cpas", "cycles/arcsec"),
                ("_hz", "Hz"),
                ("_rad", "rad"),
                ("_m", "m"),
                ("_s", "s"),
            ];
            let (key, unit) = units
                .iter()
                .find_map(|(sfx, u)| k.strip_suffix(sfx).map(|h| (h, *u)))
                .unwrap_or((k.as_str(), ""));
            let key = key.replace('_', " ");
            Some(if unit.is_empty() {
                format!("{key} = {v}")
            } else {
                format!("{key} = {v} {unit}")
            })
        })
        .collect();
    let mut line = String::new();
    for item in items {
        if line.len() + item.len() > 125 {
            line.push_str(", …");
            break;
        }
        if !line.is_empty() {
            line.push_str(", ");
        }
        line.push_str(&item);
    }
    line
}
