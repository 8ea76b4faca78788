//! `route.html` (and `compare.html`, `route-fan.html`, `sweep.html`: `many.rs`): one file that
//! opens offline and plays the route, or the routes, in 3-D. three.js and its
//! OrbitControls (r170, `src/output/view/vendor/README.md`) are embedded whole as
//! modules an import map names; the page's own script is `route.js`; the route is a JSON block
//! in the page.

use super::many::{FAN_ORANGE, Page3d, Shown};
use super::{PoseAt, View3d};
use base64::Engine;
use serde_json::{Value, json};

const THREE: &str = include_str!("vendor/three.module.min.js");
const ORBIT_CONTROLS: &str = include_str!("vendor/OrbitControls.js");
const THREE_LICENSE: &str = include_str!("vendor/LICENSE");
const SCRIPT: &str = include_str!("route.js");

/// The three.js release embedded.
pub const THREE_VERSION: &str = "0.170.0";

/// `x` rounded to `digits` decimals (the page's data need no more).
fn round(x: f64, digits: i32) -> f64 {
    let s = 10f64.powi(digits);
    let r = (x * s).round() / s;
    if r == 0.0 { 0.0 } else { r }
}

fn flat<const N: usize>(items: &[[f64; N]], digits: i32) -> Vec<f64> {
    items
        .iter()
        .flat_map(|p| p.iter().map(move |v| round(*v, digits)))
        .collect()
}

/// One route as the page reads it (`route.js`): flat arrays, metres to 0.1 mm.
fn route_data(shown: &Shown) -> Value {
    let view = &shown.view;
    let poses = &view.poses;
    let col = |f: &dyn Fn(&PoseAt) -> f64, digits: i32| -> Vec<f64> {
        poses.iter().map(|p| round(f(p), digits)).collect()
    };
    let touch: Vec<String> = poses
        .iter()
        .map(|p| {
            p.touch
                .iter()
                .map(|t| char::from(b'0' + t.code()))
                .collect()
        })
        .collect();
    json!({
        "label": shown.label,
        "color": shown.color,
        "dynamics": view.dynamics,
        "block": {
            "shape": view.shape,
            "positions": flat(&view.block.positions, 4),
            "triangles": view.block.triangles.iter().flatten().collect::<Vec<_>>(),
        },
        "points": flat(&view.points, 4),
        "corners": view.corners,
        "poses": {
            "t": col(&|p| p.t_s, 6),
            "at": poses.iter().flat_map(|p| p.at.map(|v| round(v, 5))).collect::<Vec<_>>(),
            "q": poses.iter().flat_map(|p| p.rotation.map(|v| round(v, 7))).collect::<Vec<_>>(),
            "cm": poses.iter().flat_map(|p| p.cm.map(|v| round(v, 5))).collect::<Vec<_>>(),
            "travel": col(&|p| p.travel_m, 5),
            "theta": col(&|p| p.theta_deg, 4),
            "alpha": col(&|p| p.alpha_deg, 4),
            "beta": col(&|p| p.beta_deg, 4),
            "touch": touch,
        },
        "force": view.force.as_ref().map(|f| json!({
            "tail": f.tail.map(|v| round(v, 4)),
            "head": f.head.map(|v| round(v, 4)),
            "size_n": f.size_n,
            "eccentricity_m": f.eccentricity_m,
        })),
        "end": {
            "reason": view.reason,
            "t_s": view.end_t_s,
            "travel_m": view.travel_m,
            "detail": view.detail,
        },
    })
}

/// A page's data as `route.js` reads it: its mode, the foundation, each route, and the fan's
/// paths as one flat array of points with where each path starts.
pub fn page_data(page: &Page3d) -> Value {
    let fan = page.fan.as_ref().map(|f| {
        let mut starts = Vec::with_capacity(f.paths.len());
        let mut points = Vec::new();
        for p in &f.paths {
            starts.push(points.len() / 3);
            // To the centimetre: a thousand paths keep the page under 2 MB.
            points.extend(flat(p, 2));
        }
        json!({
            "label": f.label,
            "color": FAN_ORANGE,
            "routes": f.routes,
            "starts": starts,
            "points": points,
        })
    });
    json!({
        "mode": page.mode,
        "name": page.name,
        "title": page.title,
        "three": THREE_VERSION,
        "L": page.l_m,
        "ground": {
            "positions": flat(&page.ground.positions, 4),
            "colors": flat(&page.ground.colors, 3),
        },
        "routes": page.routes.iter().map(route_data).collect::<Vec<_>>(),
        "fan": fan,
        "notes": page.notes,
    })
}

/// Text for inside an HTML element: `&`, `<` and `>` escaped.
fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// `route.html`: the page of one route.
pub fn page(view: &View3d) -> Result<String, serde_json::Error> {
    page_of(&Page3d::single(view.clone()))
}

/// Any page: one route, both dynamics, or a fan.
pub fn page_of(page: &Page3d) -> Result<String, serde_json::Error> {
    let engine = base64::engine::general_purpose::STANDARD;
    let module = |src: &str| format!("data:text/javascript;base64,{}", engine.encode(src));
    let imports = serde_json::to_string(&json!({
        "imports": {
            "three": module(THREE),
            "three/addons/controls/OrbitControls.js": module(ORBIT_CONTROLS),
        }
    }))?;
    // JSON inside <script>: "</script" would end the element and "<!--" change how it is
    // read; `<` appears in JSON only within strings, where "\u003c" is the same character.
    let data = serde_json::to_string(&page_data(page))?.replace('<', "\\u003c");
    let title = escape(&format!("{} (slideroute)", page.title));
    Ok(format!(
        r#"<!DOCTYPE html>
<html lang="en">
<head>
<meta charset="utf-8">
<meta name="viewport" content="width=device-width, initial-scale=1">
<title>{title}</title>
<!-- three.js r{THREE_VERSION} and its OrbitControls are embedded below, unchanged, under their licence:
{licence}-->
<style>
  html, body {{ margin: 0; height: 100%; overflow: hidden; font: 14px/1.35 system-ui, sans-serif; background: #f4f1ea; color: #222; }}
  #view {{ position: absolute; inset: 0; width: 100%; height: 100%; display: block; }}
  #panel {{ position: absolute; left: 10px; top: 10px; max-width: 460px; padding: 8px 12px; background: rgba(255,255,255,0.88); border-radius: 6px; box-shadow: 0 1px 4px rgba(0,0,0,0.25); }}
  #panel h1 {{ font-size: 16px; margin: 0 0 4px; }}
  #readout {{ font-variant-numeric: tabular-nums; font-size: 15px; margin: 4px 0; }}
  #controls {{ position: absolute; left: 10px; right: 10px; bottom: 10px; display: flex; gap: 8px; align-items: center; padding: 6px 10px; background: rgba(255,255,255,0.88); border-radius: 6px; box-shadow: 0 1px 4px rgba(0,0,0,0.25); }}
  #slider {{ flex: 1; }}
  button, select {{ font: inherit; }}
  #legend span {{ display: inline-block; width: 10px; height: 10px; border-radius: 5px; margin: 0 3px 0 8px; }}
  #status {{ display: none; }}
  .note {{ color: #555; font-size: 13px; }}
</style>
<script type="importmap">{imports}</script>
</head>
<body>
<canvas id="view"></canvas>
<div id="panel">
  <h1 id="title"></h1>
  <div id="readout"></div>
  <div id="legend" class="note"></div>
  <div id="end" class="note"></div>
</div>
<div id="controls">
  <button id="play" type="button">pause</button>
  <input id="slider" type="range" min="0" max="1000" step="1" value="0" aria-label="time">
  <label>speed <select id="speed">
    <option value="0.1">0.1×</option><option value="0.25">0.25×</option><option value="0.5">0.5×</option>
    <option value="1" selected>1×</option><option value="2">2×</option><option value="4">4×</option>
  </select></label>
  <button id="fit" type="button">fit</button>
  <button id="plan" type="button">plan</button>
  <button id="side" type="button">side</button>
</div>
<pre id="status"></pre>
<script type="application/json" id="route-data">{data}</script>
<script type="module">
{SCRIPT}
</script>
</body>
</html>
"#,
        licence = escape(THREE_LICENSE).replace("--", "- -"),
    ))
}
