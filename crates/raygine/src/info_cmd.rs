//! `raygine info`: what a scene holds (unit, handedness, bounds, triangles, materials, lights,
//! camera), as text or JSON.

use crate::cli::InfoArgs;
use crate::cli_support::load_scene;
use anyhow::Result;
use serde_json::{Value, json};
use tracer_core::light::daylight::Daylight;
use tracer_core::scene::{LoadedScene, Material};

pub fn run(args: &InfoArgs) -> Result<()> {
    let loaded = load_scene(&args.scene)?;
    for w in &loaded.warnings {
        eprintln!("warning: {w}");
    }
    let mut info = describe(&loaded);
    tidy_numbers(&mut info);
    if args.json {
        println!("{}", serde_json::to_string_pretty(&info)?);
    } else {
        print_text(&info);
    }
    Ok(())
}

fn material_json(name: &str, m: &Material) -> Value {
    let mut v = json!({
        "name": name,
        "emission_cd_m2": m.emission_cd_m2,
        "emission_color": m.emission_color,
        "emission_sides": m.emission_sides,
    });
    let model = match (&m.pbr, &m.pane) {
        (_, Some(g)) => json!({
            "kind": "pane",
            "ior": m.ior,
            "transmittance": g.transmittance,
        }),
        (Some(p), None) => json!({
            "base_color": p.base_color,
            "metallic": p.metallic,
            "roughness": p.roughness,
            "transmission": p.transmission,
            "ior": m.ior,
        }),
        (None, None) => json!({"kd": m.kd, "ks": m.ks, "glossiness": m.glossiness}),
    };
    if let (Some(v), Value::Object(model)) = (v.as_object_mut(), model) {
        v.extend(model);
    }
    v
}

/// The JSON description (also the source of the text form).
pub fn describe(loaded: &LoadedScene) -> Value {
    let (scene, setup) = (&loaded.scene, &loaded.setup);
    let materials: Vec<Value> = (0..scene.slots.len() as u32)
        .map(|slot| {
            let m = setup
                .materials
                .get(slot as usize)
                .copied()
                .unwrap_or_default();
            let mut j = material_json(&scene.slot_label(slot), &m);
            if let Some(set) = m.textures.and_then(|s| scene.texture_sets.get(s as usize)) {
                j["maps"] = set
                    .named()
                    .into_iter()
                    .map(|(name, t)| {
                        let file = scene
                            .textures
                            .get(t.texture as usize)
                            .map_or("?", |x| x.name.as_str());
                        json!({"map": name, "texture": file})
                    })
                    .collect();
                if set.cuts() {
                    j["alpha"] = json!(format!("{:?}", set.alpha_mode).to_lowercase());
                }
            }
            j
        })
        .collect();
    let textures: Vec<Value> = scene
        .textures
        .iter()
        .map(|t| {
            json!({
                "name": t.name,
                "width": t.width,
                "height": t.height,
                "channels": t.channels,
                "bytes": t.bytes(),
            })
        })
        .collect();
    let texture_bytes: usize = scene.textures.iter().map(|t| t.bytes()).sum();
    let lights: Vec<Value> = setup.lights.iter().map(|l| json!(l.summary())).collect();
    // (+ 0.0: no lights sum to −0.0, printed as such.)
    let total_flux_lm: f32 = setup.lights.iter().map(|l| l.flux_lm()).sum::<f32>() + 0.0;
    let b = scene.bounds;
    json!({
        "name": scene.name,
        "unit": setup.unit.symbol(),
        "handedness": match setup.handedness {
            tracer_core::scene::Handedness::Left => "left",
            tracer_core::scene::Handedness::Right => "right",
        },
        "bounds": {"min": b.min.to_array(), "max": b.max.to_array()},
        "triangles": scene.triangle_count(),
        "stored_triangles": scene.stored_triangle_count(),
        "instances": scene.instance_count(),
        "materials": materials,
        "textures": textures,
        "texture_bytes": texture_bytes,
        "lights": lights,
        "total_flux_lm": total_flux_lm,
        "camera": {
            "position": setup.camera.position,
            "look_at": setup.camera.look_at,
            "up": setup.camera.up,
            "fov_deg": setup.camera.fov_deg,
            "projection": setup.camera.projection.name(),
            "width": setup.camera.width,
            "resolution": scene.design.resolution,
        },
        "grids": setup.grids.iter().map(|g| json!({"name": g.name, "points": g.point_count()})).collect::<Vec<_>>(),
        "daylight": setup.daylight.as_ref().map(|d| daylight_json(d, setup.handedness)),
        "sun": setup.sun.map(|s| json!({
            "direction": s.direction,
            "diameter_deg": s.diameter_deg,
            "normal_illuminance_lx": s.normal_illuminance_lx,
        })),
        "environment": setup.environment.as_ref().map(|e| match &e.source {
            tracer_core::light::EnvironmentSource::Uniform { luminance_cd_m2, color } => json!({
                "kind": "uniform", "luminance_cd_m2": luminance_cd_m2, "color": color,
                "rotation_deg": e.rotation_deg,
            }),
            tracer_core::light::EnvironmentSource::Map(map) => json!({
                "kind": "map", "map": map.file.display().to_string(), "scale": e.scale, "rotation_deg": e.rotation_deg,
            }),
        }),
    })
}

/// The place and time of `[daylight]` and where the sun is then.
fn daylight_json(d: &Daylight, handedness: tracer_core::scene::Handedness) -> Value {
    let sun = d.sun();
    let p = &d.place_time;
    json!({
        "latitude_deg": p.latitude_deg,
        "longitude_east_deg": p.longitude_deg,
        "date": p.date.to_string(),
        "time": p.time.to_string(),
        "timezone_h": p.timezone_h,
        "daylight_saving": p.daylight_saving,
        "sun_altitude_deg": sun.altitude_deg,
        "sun_azimuth_deg": sun.azimuth_deg,
        "sun_direction": d
            .sun_direction(handedness == tracer_core::scene::Handedness::Right)
            .to_array(),
        "sun_normal_illuminance_lx": d.sun_normal_illuminance_lx,
        "sky": d.sky.map(|s| json!({
            "model": s.model.name(),
            "zenith_luminance_cd_m2": s.zenith_luminance_cd_m2,
            "horizontal_illuminance_lx": s.horizontal_illuminance(),
            "ground_reflectance": s.ground_reflectance,
            "perez": s.perez.map(|p| json!({
                "epsilon": p.epsilon,
                "delta": p.delta,
                "coefficients": p.coefficients,
            })),
        })),
    })
}

/// Every fractional number as the shortest decimal that gives back its f32 (the scene's
/// precision): 0.725, not 0.7250000238418579. Whole numbers stay as they are.
pub fn tidy_numbers(v: &mut Value) {
    match v {
        Value::Number(n) if n.is_f64() => {
            if let Some(x) = n.as_f64().filter(|x| x.is_finite() && x.fract() != 0.0) {
                let short: f64 = (x as f32).to_string().parse().unwrap_or(x);
                if let Some(m) = serde_json::Number::from_f64(short) {
                    *n = m;
                }
            }
        }
        Value::Array(a) => a.iter_mut().for_each(tidy_numbers),
        Value::Object(o) => o.values_mut().for_each(tidy_numbers),
        _ => {}
    }
}

fn print_text(v: &Value) {
    let unit = v["unit"].as_str().unwrap_or("mm");
    println!("scene {}", v["name"]);
    println!(
        "unit {unit}, {}-handed",
        v["handedness"].as_str().unwrap_or("?")
    );
    println!(
        "bounds {} .. {} ({unit}), {} triangles{}",
        v["bounds"]["min"],
        v["bounds"]["max"],
        v["triangles"],
        match v["instances"].as_u64() {
            Some(k) if k > 0 => format!(" ({} stored, {k} instances)", v["stored_triangles"]),
            _ => String::new(),
        }
    );
    println!("materials (sidecar keys):");
    for m in v["materials"].as_array().into_iter().flatten() {
        let mut line = if m["kind"] == "pane" {
            format!(
                "  {}: thin glass pane, ior {}, {}",
                m["name"],
                m["ior"],
                match m["transmittance"].as_f64() {
                    Some(t) => format!("normal-incidence transmittance {t}"),
                    None => "clear (no absorption)".to_owned(),
                }
            )
        } else if m.get("base_color").is_some() {
            format!(
                "  {}: base_color {} metallic {} roughness {}",
                m["name"], m["base_color"], m["metallic"], m["roughness"]
            )
        } else {
            format!(
                "  {}: kd {} ks {} glossiness {}",
                m["name"], m["kd"], m["ks"], m["glossiness"]
            )
        };
        if m["transmission"].as_f64().unwrap_or(0.0) > 0.0 {
            line.push_str(&format!(
                ", transmission {} (ior {})",
                m["transmission"], m["ior"]
            ));
        }
        if m["emission_cd_m2"].as_f64().unwrap_or(0.0) > 0.0 {
            line.push_str(&format!(
                ", emits {} cd/m² ({} faces)",
                m["emission_cd_m2"], m["emission_sides"]
            ));
        }
        for map in m["maps"].as_array().into_iter().flatten() {
            line.push_str(&format!(
                ", {} map {}",
                map["map"].as_str().unwrap_or("?"),
                map["texture"].as_str().unwrap_or("?")
            ));
        }
        if let Some(a) = m["alpha"].as_str() {
            line.push_str(&format!(", alpha {a}"));
        }
        println!("{line}");
    }
    let textures = v["textures"].as_array().map_or(&[][..], |a| a.as_slice());
    if !textures.is_empty() {
        println!(
            "textures: {} images, {:.1} MB of texels",
            textures.len(),
            v["texture_bytes"].as_f64().unwrap_or(0.0) / 1e6
        );
        for t in textures {
            println!(
                "  {}: {} x {} texels, {} channels, {:.2} MB",
                t["name"].as_str().unwrap_or("?"),
                t["width"],
                t["height"],
                t["channels"],
                t["bytes"].as_f64().unwrap_or(0.0) / 1e6
            );
        }
    }
    println!(
        "lights: {:.1} lm in all",
        v["total_flux_lm"].as_f64().unwrap_or(0.0)
    );
    for (i, l) in v["lights"].as_array().into_iter().flatten().enumerate() {
        let mut line = format!(
            "  {}: {} at {} ({unit}), {:.1} lm",
            i + 1,
            l["kind"].as_str().unwrap_or("?"),
            l["position"],
            l["flux_lm"].as_f64().unwrap_or(0.0)
        );
        if let Some(cd) = l["intensity_cd"].as_f64() {
            line.push_str(&format!(
                ", {cd:.1} cd{}",
                if l["kind"] == "point" { "" } else { " max" }
            ));
        }
        if let Some(aim) = l.get("aim") {
            line.push_str(&format!(", aim {aim}"));
        }
        if let Some(file) = l.get("file") {
            line.push_str(&format!(", file {file}"));
        }
        println!("{line}");
    }
    let c = &v["camera"];
    let view = match c["projection"].as_str().unwrap_or("perspective") {
        "perspective" => format!("field of view {}°", c["fov_deg"]),
        "equirectangular" => "equirectangular, 360° x 180°".to_owned(),
        "orthographic" => match c["width"].as_f64() {
            Some(w) => format!(
                "orthographic, {w} {} across",
                v["unit"].as_str().unwrap_or("")
            ),
            None => "orthographic, as wide as the perspective view at the look-at point".into(),
        },
        fisheye => format!("{fisheye}, {}° across the image circle", c["fov_deg"]),
    };
    println!(
        "camera at {} looking at {}, up {}, {view}",
        c["position"], c["look_at"], c["up"]
    );
    if let (Some(w), Some(h)) = (c["resolution"][0].as_u64(), c["resolution"][1].as_u64()) {
        println!("designed for {w} x {h} pixels");
    }
    for g in v["grids"].as_array().into_iter().flatten() {
        println!("grid {}: {} points", g["name"], g["points"]);
    }
    let s = &v["sun"];
    if !s.is_null() {
        println!(
            "sun (the file's distant light): towards {}, {}° across, {:.1} lx on a plane facing it",
            s["direction"],
            s["diameter_deg"],
            s["normal_illuminance_lx"].as_f64().unwrap_or(0.0)
        );
    }
    let e = &v["environment"];
    match e["kind"].as_str() {
        Some("uniform") => println!(
            "environment: uniform, {:.1} cd/m²",
            e["luminance_cd_m2"].as_f64().unwrap_or(0.0)
        ),
        Some(_) => println!(
            "environment: map {}, {} cd/m² per unit, turned {:.1}° about the vertical",
            e["map"],
            e["scale"],
            e["rotation_deg"].as_f64().unwrap_or(0.0)
        ),
        None => {}
    }
    let d = &v["daylight"];
    if !d.is_null() {
        let f = |k: &str| d[k].as_f64().unwrap_or(f64::NAN);
        let (lat, lon) = (f("latitude_deg"), f("longitude_east_deg"));
        println!(
            "daylight: {} {} (UTC{:+}{}), {:.4}° {}, {:.4}° {}: sun at altitude {:.2}° \
             (refraction included), azimuth {:.2}° from north through east, towards {} in the \
             scene",
            d["date"].as_str().unwrap_or("?"),
            d["time"].as_str().unwrap_or("?"),
            f("timezone_h"),
            if d["daylight_saving"].as_bool() == Some(true) {
                ", summer time"
            } else {
                ""
            },
            lat.abs(),
            if lat >= 0.0 { "N" } else { "S" },
            lon.abs(),
            if lon >= 0.0 { "E" } else { "W" },
            f("sun_altitude_deg"),
            f("sun_azimuth_deg"),
            d["sun_direction"]
        );
        let sky = &d["sky"];
        if !sky.is_null() {
            println!(
                "sky: {} with zenith luminance {:.1} cd/m², unobstructed horizontal illuminance \
                 {:.0} lx, ground reflectance {}",
                sky["model"].as_str().unwrap_or("?"),
                sky["zenith_luminance_cd_m2"].as_f64().unwrap_or(f64::NAN),
                sky["horizontal_illuminance_lx"]
                    .as_f64()
                    .unwrap_or(f64::NAN),
                sky["ground_reflectance"]
            );
            let p = &sky["perez"];
            if !p.is_null() {
                println!(
                    "perez: clearness ε {:.4}, brightness Δ {:.4}, coefficients a-e {}",
                    p["epsilon"].as_f64().unwrap_or(f64::NAN),
                    p["delta"].as_f64().unwrap_or(f64::NAN),
                    p["coefficients"]
                );
            }
        }
        if let Some(e) = d["sun_normal_illuminance_lx"].as_f64() {
            if f("sun_altitude_deg") > 0.0 {
                println!(
                    "sun: a 0.533° disc giving {e:.0} lx on a plane facing it, {:.0} lx on the \
                     horizontal",
                    e * f("sun_altitude_deg").to_radians().sin()
                );
            } else {
                println!("sun: below the horizon, so it lights nothing");
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn numbers_read_as_the_scene_wrote_them() {
        let mut v = json!({"kd": [0.725f32, 0.71f32], "fov": 39.3f32, "n": 30, "z": -559.2f32});
        tidy_numbers(&mut v);
        assert_eq!(
            v.to_string(),
            r#"{"fov":39.3,"kd":[0.725,0.71],"n":30,"z":-559.2}"#
        );
    }
}
