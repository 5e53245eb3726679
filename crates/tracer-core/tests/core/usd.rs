//! USD scenes (`formats::usd`) against files Pixar's own library wrote and against formulas.
//!
//! - `assets/usd/cornell.usda`, `.usdc` and `.usdz` (written by usd-core with
//!   `scripts/usd/make_cornell.py`, not by the crate under test) load to the same description,
//!   and the box renders pixel for pixel as `cornell.gltf`, the same scene written as glTF.
//! - Z-up files in centimetres stand up at the right size; composition arcs (sublayers,
//!   references, payloads, variants, instancing) compose.
//! - Light units: a SphereLight against E = I cos θ / R² with I = L π r², a RectLight against
//!   the exact rectangle form factor, a normalised DistantLight against its intensity in lux, a
//!   uniform DomeLight against π L; a dome texture's orientation is OpenEXR's.
//! - Bad files (truncated, corrupt, cyclic, missing layers, bad meshes) are errors naming the
//!   file and prim, never panics.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use crate::gi_support::{form_factor, v3};
use glam::DVec3;
use std::f64::consts::PI;
use std::path::{Path, PathBuf};
use tracer_core::formats::{ReadOptions, SceneDescription, read_scene, usd};
use tracer_core::integrator::IntegratorKind;
use tracer_core::measure::{MeasureSettings, measure_grids};
use tracer_core::render::{RenderSettings, render};
use tracer_core::scene::{LoadOptions, LoadedScene, load};

/// A saved fuzz find (`fuzz/regressions/usd/`).
fn regression(name: &str) -> Vec<u8> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/regressions/usd");
    std::fs::read(dir.join(name)).unwrap()
}

fn asset(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("../../assets/usd")
        .join(name)
}

struct Scratch(PathBuf);

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

fn scratch(name: &str) -> Scratch {
    let d = std::env::temp_dir().join(format!("raygine-usd-{name}-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    Scratch(d)
}

impl Scratch {
    fn write(&self, name: &str, text: &str) -> PathBuf {
        let p = self.0.join(name);
        std::fs::write(&p, text).unwrap();
        p
    }
}

/// A description without the file it came from (the three files' descriptions differ there).
fn without_path(mut d: SceneDescription) -> SceneDescription {
    d.path = PathBuf::new();
    for m in &mut d.meshes {
        m.source = PathBuf::new();
        if let Some(p) = &mut m.placement {
            p.source = PathBuf::new();
        }
    }
    for m in &mut d.materials {
        m.source = PathBuf::new();
    }
    for l in d.lights.iter_mut().flatten() {
        l.source = PathBuf::new();
    }
    d.notes.clear();
    d
}

#[test]
fn the_three_encodings_of_the_cornell_box_load_alike() {
    let a = read_scene(&asset("cornell.usda")).unwrap();
    let c = read_scene(&asset("cornell.usdc")).unwrap();
    let z = read_scene(&asset("cornell.usdz")).unwrap();
    assert_eq!(a.meshes.len(), 8, "7 meshes and the RectLight");
    assert_eq!(a.triangle_count(), 32);
    assert_eq!(a.materials.len(), 4);
    assert_eq!(a.metres_per_unit, Some(1.0));
    let light = a.meshes.iter().find(|m| m.name == "/World/Light").unwrap();
    let emission = a.materials[light.parts[0].material.unwrap()]
        .emission
        .unwrap();
    assert_eq!(
        emission.luminance_cd_m2, 6000.0,
        "intensity 3000 x 2^exposure 1"
    );
    // The RectLight faces down: its triangles' (v1 - v0) x (v2 - v0) point to -Y.
    for t in &light.triangles {
        let [p, q, r] = t.map(|i| DVec3::from(light.positions[i as usize]));
        assert!((q - p).cross(r - p).normalize().dot(-DVec3::Y) > 0.999_999);
    }
    let camera = a.camera.unwrap();
    assert_eq!(camera.position, [0.0, 1.0, 3.5]);
    let fov = 2.0 * (12.0f64 / 30.0).atan().to_degrees();
    assert!((f64::from(camera.fov_deg) - fov).abs() < 1e-4);
    let a = without_path(a);
    assert_eq!(a, without_path(c), ".usdc");
    assert_eq!(a, without_path(z), ".usdz");
}

fn render_direct(loaded: &LoadedScene, camera_from: &LoadedScene) -> tracer_core::render::Film {
    let mut setup = loaded.setup.clone();
    setup.camera = camera_from.setup.camera;
    let settings = RenderSettings {
        width: 96,
        height: 96,
        samples_per_pixel: 4,
        integrator: IntegratorKind::Direct,
        ..RenderSettings::default()
    };
    render(&loaded.scene, &setup, &settings).0
}

#[test]
fn the_usd_cornell_box_renders_pixel_for_pixel_as_its_gltf_twin() {
    let gltf = load(&asset("cornell.gltf"), &LoadOptions::default()).unwrap();
    let ref_film = render_direct(&gltf, &gltf);
    let lit = ref_film
        .pixels()
        .filter(|p| p.mean_luminance() > 0.0)
        .count();
    assert!(lit > ref_film.len() / 2, "the box is lit: {lit} pixels");
    for file in ["cornell.usda", "cornell.usdc", "cornell.usdz"] {
        let usd = load(&asset(file), &LoadOptions::default()).unwrap();
        assert!(
            (usd.setup.camera.fov_deg - gltf.setup.camera.fov_deg).abs() < 1e-4
                && usd.setup.camera.position == gltf.setup.camera.position,
            "{file}: the same camera"
        );
        // Drawn through the glTF's camera: the two readers round the lens angle differently
        // (f32 radians in glTF, f64 in USD) by at most an ulp.
        let film = render_direct(&usd, &gltf);
        let differing = (0..film.len())
            .filter(|&i| film.pixel(i) != ref_film.pixel(i))
            .count();
        println!(
            "{file}: {differing} of {} pixels differ from glTF's",
            film.len()
        );
        assert_eq!(differing, 0, "{file}");
    }
}

/// A cube of `size` units standing on z = 0 in a Z-up stage.
fn z_up_cube(size: f64, metres: Option<f64>) -> String {
    let h = size / 2.0;
    let mpu = metres.map_or_else(String::new, |m| format!("    metersPerUnit = {m}\n"));
    format!(
        "#usda 1.0\n(\n    upAxis = \"Z\"\n{mpu})\n\ndef Mesh \"Cube\"\n{{\n    \
         int[] faceVertexCounts = [4, 4, 4, 4, 4, 4]\n    \
         int[] faceVertexIndices = [0, 3, 2, 1, 4, 5, 6, 7, 0, 1, 5, 4, 1, 2, 6, 5, 2, 3, 7, 6, 3, 0, 4, 7]\n    \
         point3f[] points = [(-{h}, -{h}, 0), ({h}, -{h}, 0), ({h}, {h}, 0), (-{h}, {h}, 0), \
         (-{h}, -{h}, {size}), ({h}, -{h}, {size}), ({h}, {h}, {size}), (-{h}, {h}, {size})]\n    \
         uniform token subdivisionScheme = \"none\"\n}}\n"
    )
}

#[test]
fn a_z_up_file_in_centimetres_stands_on_its_base_at_its_size() {
    let dir = scratch("zup");
    let path = dir.write("cube.usda", &z_up_cube(100.0, None));
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    // metersPerUnit absent: USD's 0.01, centimetres.
    assert_eq!(loaded.setup.unit, tracer_core::scene::LengthUnit::Cm);
    let b = loaded.scene.bounds;
    println!("bounds {:?} .. {:?} cm", b.min, b.max);
    assert_eq!(b.min.to_array(), [-50.0, 0.0, -50.0]);
    assert_eq!(b.max.to_array(), [50.0, 100.0, 50.0]);
    // 100 units of 0.01 m: 1 m wide, and its base (z = 0) is the floor (y = 0).
    let width_m = f64::from(b.max.x - b.min.x) * 0.01;
    assert!((width_m - 1.0).abs() < 1e-12);
}

const SQUARE: &str = "int[] faceVertexCounts = [4]\n        int[] faceVertexIndices = [0, 1, 2, 3]\n        \
    point3f[] points = [(0, 0, 0), (1, 0, 0), (1, 1, 0), (0, 1, 0)]";

#[test]
fn composition_arcs_compose() {
    let dir = scratch("compose");
    dir.write(
        "part.usda",
        &format!(
            "#usda 1.0\n(\n    defaultPrim = \"Part\"\n)\ndef Xform \"Part\"\n{{\n    \
             def Mesh \"Square\"\n    {{\n        {SQUARE}\n    }}\n}}\n"
        ),
    );
    dir.write(
        "sub.usda",
        &format!(
            "#usda 1.0\ndef Mesh \"FromSublayer\"\n{{\n    {SQUARE}\n    \
             double3 xformOp:translate = (0, 0, -5)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}}\n"
        ),
    );
    let root = dir.write(
        "root.usda",
        &format!(
            "#usda 1.0\n(\n    metersPerUnit = 1\n    upAxis = \"Y\"\n    subLayers = [@./sub.usda@]\n)\n\
             def Xform \"Referenced\" (\n    references = @./part.usda@\n)\n{{\n    \
             double3 xformOp:translate = (10, 0, 0)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}}\n\
             def Xform \"Payloaded\" (\n    payload = @./part.usda@\n)\n{{\n    \
             double3 xformOp:translate = (20, 0, 0)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}}\n\
             def Xform \"Variants\" (\n    variants = {{\n        string size = \"big\"\n    }}\n    \
             prepend variantSets = \"size\"\n)\n{{\n    variantSet \"size\" = {{\n        \
             \"big\" {{\n            def Mesh \"Big\"\n            {{\n                {SQUARE}\n                \
             float3 xformOp:scale = (3, 3, 3)\n                uniform token[] xformOpOrder = [\"xformOp:scale\"]\n            }}\n        }}\n        \
             \"small\" {{\n            def Mesh \"Small\"\n            {{\n                {SQUARE}\n            }}\n        }}\n    }}\n}}\n\
             def Xform \"Hidden\"\n{{\n    token visibility = \"invisible\"\n    def Mesh \"Gone\"\n    {{\n        {SQUARE}\n    }}\n}}\n\
             def Mesh \"Proxy\"\n{{\n    uniform token purpose = \"proxy\"\n    {SQUARE}\n}}\n"
        ),
    );
    let d = read_scene(&root).unwrap();
    let names: Vec<&str> = d.meshes.iter().map(|m| m.name.as_str()).collect();
    println!("meshes: {names:?}\nnotes: {:#?}", d.notes);
    for expected in [
        "/FromSublayer",
        "/Referenced/Square",
        "/Payloaded/Square",
        "/Variants/Big",
    ] {
        assert!(names.contains(&expected), "{expected} in {names:?}");
    }
    assert!(
        !names.contains(&"/Variants/Small"),
        "the selected variant only"
    );
    assert!(
        !names
            .iter()
            .any(|n| n.contains("Gone") || n.contains("Proxy"))
    );
    let mesh = |n: &str| d.meshes.iter().find(|m| m.name == n).unwrap();
    let max_x = |n: &str| {
        mesh(n)
            .positions
            .iter()
            .map(|p| p[0])
            .fold(f64::MIN, f64::max)
    };
    assert_eq!(
        max_x("/Referenced/Square"),
        11.0,
        "the reference is moved by its prim"
    );
    assert_eq!(max_x("/Payloaded/Square"), 21.0);
    assert_eq!(max_x("/Variants/Big"), 3.0, "the variant's own scale");
    assert!(mesh("/FromSublayer").positions.iter().all(|p| p[2] == -5.0));
}

#[test]
fn instanceable_prims_store_their_prototype_once() {
    let dir = scratch("instances");
    let mut text = format!(
        "#usda 1.0\n(\n    metersPerUnit = 1\n)\nclass Xform \"Proto\"\n{{\n    def Mesh \"Geom\"\n    {{\n        \
         {SQUARE}\n    }}\n}}\n"
    );
    for i in 0..5 {
        text += &format!(
            "def Xform \"Copy{i}\" (\n    instanceable = true\n    inherits = </Proto>\n)\n{{\n    \
             double3 xformOp:translate = ({i}, 0, 0)\n    float xformOp:rotateY = {}\n    \
             uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:rotateY\"]\n}}\n",
            30 * i
        );
    }
    let path = dir.write("copies.usda", &text);
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    let scene = &loaded.scene;
    assert_eq!(scene.triangle_count(), 10);
    assert_eq!(scene.stored_triangle_count(), 2, "one square stored");
    assert_eq!(scene.instance_count(), 5);
    let names: Vec<&str> = scene.breps.iter().map(|b| b.name.as_str()).collect();
    assert_eq!(
        names,
        [
            "/Copy0/Geom",
            "/Copy1/Geom",
            "/Copy2/Geom",
            "/Copy3/Geom",
            "/Copy4/Geom"
        ]
    );
    // Copy 3 is turned 90° about y and moved to x = 3: its square spans x in 3..3 (edge-on),
    // z in -1..0.
    let d = read_scene(&path).unwrap();
    let m = d.meshes[3].placement.as_ref().unwrap().world_from_local;
    let corner = m.transform_point3(DVec3::new(1.0, 0.0, 0.0));
    assert!(
        (corner - DVec3::new(3.0, 0.0, -1.0)).length() < 1e-12,
        "{corner}"
    );
}

/// A black floor 20 m square at y = 0 (facing up) and a light prim, metres.
fn floor_with(light: &str) -> String {
    format!(
        "#usda 1.0\n(\n    metersPerUnit = 1\n    upAxis = \"Y\"\n)\n\
         def Mesh \"Floor\"\n{{\n    int[] faceVertexCounts = [4]\n    int[] faceVertexIndices = [0, 1, 2, 3]\n    \
         point3f[] points = [(-10, 0, -10), (-10, 0, 10), (10, 0, 10), (10, 0, -10)]\n    \
         color3f[] primvars:displayColor = [(0, 0, 0)]\n    \
         uniform token subdivisionScheme = \"none\"\n}}\n{light}"
    )
}

fn measure_on(
    dir: &Scratch,
    usda: &str,
    grids: &str,
    samples: u32,
) -> Vec<tracer_core::measure::GridResult> {
    let scene = dir.write("lit.usda", usda);
    let sidecar = dir.write("lit.raygine.toml", grids);
    let loaded = load(
        &scene,
        &LoadOptions {
            sidecar: Some(&sidecar),
            ..LoadOptions::default()
        },
    )
    .unwrap();
    let settings = MeasureSettings {
        integrator: IntegratorKind::Direct,
        max_bounces: None,
        samples,
        time_limit: None,
        target_error: None,
    };
    measure_grids(&loaded.scene, &loaded.setup, &settings)
}

#[test]
fn a_sphere_light_is_a_point_of_l_pi_r_squared_beyond_ten_radii() {
    let dir = scratch("sphere");
    // r = 1 cm at 1 m: L = 10^6 cd/m² (intensity 2.5 x 10^5 x 2^2), I = L π r² = 314.16 cd.
    let (radius, height, nits) = (0.01, 1.0, 1.0e6);
    let light = format!(
        "def SphereLight \"Bulb\"\n{{\n    float inputs:intensity = 250000\n    float inputs:exposure = 2\n    \
         float inputs:radius = {radius}\n    double3 xformOp:translate = (0, {height}, 0)\n    \
         uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}}\n"
    );
    let grids = "[[grids]]\nname = \"floor\"\norigin = [0.0, 0.0, 0.0]\nu = [2.0, 0.0, 0.0]\n\
                 v = [0.0, 0.0, 0.01]\nnu = 5\nnv = 1\nnormal = [0.0, 1.0, 0.0]\n";
    let results = measure_on(&dir, &floor_with(&light), grids, 4_000_000);
    let intensity = nits * PI * radius * radius;
    let mut worst = 0.0f64;
    for p in &results[0].points {
        let d = v3(p.position) - DVec3::new(0.0, height, 0.0);
        let cos = -d.y / d.length();
        let exact = intensity * cos / d.length_squared();
        let rel = p.illuminance_lx / exact - 1.0;
        worst = worst.max(rel.abs());
        println!(
            "x = {:.1} m: {:.3} ± {:.3} lx, I cos θ / R² = {exact:.3} lx ({:+.3} %)",
            p.position.x,
            p.illuminance_lx,
            p.std_error_lx,
            rel * 100.0
        );
        assert!(
            rel.abs() < 0.005 && (p.illuminance_lx - exact).abs() < 4.0 * p.std_error_lx,
            "within 0.5 % and the noise"
        );
    }
    println!("worst {:.3} %", worst * 100.0);
}

#[test]
fn a_treat_as_point_sphere_light_is_a_point_light_of_the_same_intensity() {
    let dir = scratch("point");
    let light = "def SphereLight \"Bulb\"\n{\n    float inputs:intensity = 1000000\n    \
                 float inputs:radius = 0.01\n    bool treatAsPoint = 1\n    \
                 double3 xformOp:translate = (0, 2, 0)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}\n";
    let path = dir.write("p.usda", &floor_with(light));
    let d = read_scene(&path).unwrap();
    let lights = d.lights.unwrap();
    assert_eq!(lights.len(), 1);
    assert_eq!(lights[0].position, [0.0, 2.0, 0.0]);
    match lights[0].distribution {
        tracer_core::formats::LightDistribution::Isotropic { intensity_cd } => {
            let exact = 1.0e6 * PI * 1e-4;
            assert!(
                (f64::from(intensity_cd) / exact - 1.0).abs() < 1e-6,
                "{intensity_cd}"
            );
        }
        ref other => panic!("{other:?}"),
    }
}

#[test]
fn a_rect_light_reads_the_rectangle_form_factor() {
    let dir = scratch("rect");
    // 1 m x 0.5 m at 0.5 m, emitting down; normalize: L = 2000 / 0.5 m² = 4000 cd/m².
    let light = "def RectLight \"Panel\"\n{\n    float inputs:intensity = 2000\n    bool inputs:normalize = 1\n    \
                 float inputs:width = 1\n    float inputs:height = 0.5\n    \
                 double3 xformOp:translate = (0, 0.5, 0)\n    float xformOp:rotateX = -90\n    \
                 uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:rotateX\"]\n}\n";
    let grids = "[[grids]]\nname = \"floor\"\norigin = [-0.8, 0.0, -0.6]\nu = [1.6, 0.0, 0.0]\n\
                 v = [0.0, 0.0, 1.2]\nnu = 3\nnv = 3\nnormal = [0.0, 1.0, 0.0]\n";
    let results = measure_on(&dir, &floor_with(light), grids, 100_000);
    let luminance = 2000.0 / 0.5;
    let corners = [
        DVec3::new(-0.5, 0.5, -0.25),
        DVec3::new(0.5, 0.5, -0.25),
        DVec3::new(0.5, 0.5, 0.25),
        DVec3::new(-0.5, 0.5, 0.25),
    ];
    for p in &results[0].points {
        let exact = PI * luminance * form_factor(v3(p.position), DVec3::Y, &corners);
        let rel = p.illuminance_lx / exact - 1.0;
        println!(
            "{}: {:.2} ± {:.2} lx, π L F = {exact:.2} lx ({:+.3} %)",
            p.position,
            p.illuminance_lx,
            p.std_error_lx,
            rel * 100.0
        );
        assert!(rel.abs() < 0.01 && (p.illuminance_lx - exact).abs() < 5.0 * p.std_error_lx);
    }
}

#[test]
fn left_handed_meshes_subsets_primvars_and_notes() {
    let dir = scratch("mesh");
    let path = dir.write(
        "m.usda",
        "#usda 1.0\n(\n    metersPerUnit = 1\n)\n\
         def Material \"Red\"\n{\n    token outputs:surface.connect = </Red/S.outputs:surface>\n    \
         def Shader \"S\"\n    {\n        uniform token info:id = \"UsdPreviewSurface\"\n        \
         color3f inputs:diffuseColor = (0.8, 0.1, 0.1)\n        token outputs:surface\n    }\n}\n\
         def Mesh \"Two\"\n{\n    int[] faceVertexCounts = [3, 4]\n    \
         int[] faceVertexIndices = [0, 1, 2, 1, 3, 4, 2]\n    \
         point3f[] points = [(0, 0, 0), (1, 0, 0), (0, 1, 0), (2, 0, 0), (2, 1, 0)]\n    \
         uniform token orientation = \"leftHanded\"\n    \
         normal3f[] primvars:normals = [(0, 0, -1)] (\n        interpolation = \"constant\"\n    )\n    \
         texCoord2f[] primvars:st = [(0, 0), (1, 0), (0, 1), (1, 0), (1, 1), (0, 1), (0, 0)] (\n        interpolation = \"faceVarying\"\n    )\n    \
         color3f[] primvars:displayColor = [(0.2, 0.4, 0.6)]\n    \
         def GeomSubset \"Quad\" (\n        prepend apiSchemas = [\"MaterialBindingAPI\"]\n    )\n    {\n        \
         uniform token elementType = \"face\"\n        uniform token familyName = \"materialBind\"\n        \
         int[] indices = [1]\n        rel material:binding = </Red>\n    }\n}\n",
    );
    let d = read_scene(&path).unwrap();
    let m = &d.meshes[0];
    assert_eq!(m.triangles.len(), 3);
    // Left-handed: the winding is reversed, so (v1 - v0) x (v2 - v0) faces -Z, as the normals.
    for t in &m.triangles {
        let [a, b, c] = t.map(|i| DVec3::from(m.positions[i as usize]));
        assert!((b - a).cross(c - a).z < 0.0);
    }
    assert_eq!(
        m.normals.len(),
        m.positions.len(),
        "constant normals per vertex"
    );
    assert!(m.normals.iter().all(|n| *n == [0.0, 0.0, -1.0]));
    // faceVarying st splits the points: one vertex per corner, V flipped.
    assert_eq!(m.positions.len(), 7);
    assert_eq!(m.uvs[0][2], [0.0, 0.0], "st (0, 1) is the image's top");
    // Parts: the unbound faces with displayColor, the subset with its material.
    assert_eq!(m.parts.len(), 2);
    assert_eq!(m.parts[1].name.as_deref(), Some("Quad"));
    assert_eq!(m.triangle_parts, [0, 1, 1]);
    let red = &d.materials[m.parts[1].material.unwrap()];
    assert_eq!(red.name, "/Red");
    assert_eq!(red.metal_rough.unwrap().base_color, [0.8, 0.1, 0.1]);
    let display = &d.materials[m.parts[0].material.unwrap()];
    assert_eq!(display.diffuse, [0.2, 0.4, 0.6]);
    // No subdivisionScheme: USD's default catmullClark, drawn as its control mesh.
    assert!(
        d.notes
            .iter()
            .any(|n| n.contains("subdivision") && n.contains("control meshes")),
        "{:#?}",
        d.notes
    );
}

#[test]
fn sidecar_keys_are_prim_paths() {
    let dir = scratch("keys");
    let scene = dir.write("k.usda", &z_up_cube(100.0, Some(0.01)));
    let sidecar = dir.write(
        "k.raygine.toml",
        "[materials.\"/Cube\"]\nkd = [0.1, 0.2, 0.3]\n",
    );
    let loaded = load(
        &scene,
        &LoadOptions {
            sidecar: Some(&sidecar),
            ..LoadOptions::default()
        },
    )
    .unwrap();
    assert!(
        loaded.warnings.iter().all(|w| !w.contains("/Cube")),
        "{:?}",
        loaded.warnings
    );
    let m = &loaded.setup.materials[0];
    assert_eq!(m.kd, [0.1, 0.2, 0.3]);
}

#[test]
fn bad_files_are_errors_naming_the_file_never_panics() {
    let dir = scratch("bad");
    let usdc = std::fs::read(asset("cornell.usdc")).unwrap();
    let usdz = std::fs::read(asset("cornell.usdz")).unwrap();
    let mut corrupt = usdc.clone();
    for (k, b) in corrupt.iter_mut().enumerate().skip(88) {
        if k % 7 == 0 {
            *b ^= 0x5a;
        }
    }
    let cases: Vec<(&str, Vec<u8>, &str)> = vec![
        ("truncated.usdc", usdc[..usdc.len() / 2].to_vec(), "USD"),
        ("truncated.usdz", usdz[..usdz.len() / 2].to_vec(), "USD"),
        ("corrupt.usdc", corrupt, ""),
        ("empty.usda", b"#usda 1.0\n".to_vec(), "nothing to draw"),
        ("text.usda", b"#usda 1.0\ndef Mesh \"M\" {\n".to_vec(), "USD"),
        (
            "cycle_a.usda",
            b"#usda 1.0\ndef \"A\" (\n    references = @./cycle_b.usda@</B>\n)\n{\n}\n".to_vec(),
            "",
        ),
        (
            "missing.usda",
            b"#usda 1.0\n(\n    subLayers = [@./not_here.usda@]\n)\n".to_vec(),
            "compose",
        ),
        (
            "counts.usda",
            b"#usda 1.0\ndef Mesh \"M\"\n{\n    int[] faceVertexCounts = [3, 3]\n    int[] faceVertexIndices = [0, 1, 2]\n    point3f[] points = [(0,0,0), (1,0,0), (0,1,0)]\n}\n".to_vec(),
            "/M: faceVertexCounts add up to 6 corners",
        ),
        (
            "index.usda",
            b"#usda 1.0\ndef Mesh \"M\"\n{\n    int[] faceVertexCounts = [3]\n    int[] faceVertexIndices = [0, 1, 9]\n    point3f[] points = [(0,0,0), (1,0,0), (0,1,0)]\n}\n".to_vec(),
            "/M: faceVertexIndices: index 9 outside the 3 points",
        ),
        (
            // The fuzzer's find: a count declaring 12 PB; openusd allocates it and the
            // process would abort, so a child process tries the file first.
            "huge.usdc",
            regression("crash-046a1824-huge-declared-count.usdc"),
            "a trial read in a child process failed, it aborted",
        ),
        (
            // The fuzzer's second find: openusd's instancing resolution recursing without end
            // on a mangled Cornell box; the trial read is stopped (3 s here, 60 s by default).
            "loop.usda",
            regression("timeout-fc6bb632-instancing-loop.usda"),
            "did not finish reading this file within 3 s",
        ),
        (
            "up.usda",
            b"#usda 1.0\n(\n    upAxis = \"X\"\n)\n".to_vec(),
            "upAxis",
        ),
    ];
    dir.write(
        "cycle_b.usda",
        "#usda 1.0\ndef \"B\" (\n    references = @./cycle_a.usda@</A>\n)\n{\n}\n",
    );
    for (name, bytes, expect) in cases {
        let path = dir.0.join(name);
        std::fs::write(&path, &bytes).unwrap();
        let options = ReadOptions {
            usd_trial_secs: Some(3.0),
            ..ReadOptions::default()
        };
        let result = std::panic::catch_unwind(|| usd::read(&path, &options));
        let Ok(result) = result else {
            panic!("{name}: panicked");
        };
        let e = result.expect_err(name).to_string();
        println!("{name}: {e}");
        assert!(
            e.starts_with(&path.display().to_string()),
            "{name} names the file: {e}"
        );
        assert!(e.contains(expect), "{name}: {e}");
    }
}

/// The Stanford bunny's mesh as a prototype placed 100 times: stored once.
#[test]
fn a_hundred_instanced_bunnies_store_one() {
    let Some(obj) = raygine_fixtures::shared("models/stanford-bunny.obj") else {
        println!("skipped: ../shared (the bunny) is absent");
        return;
    };
    let bunny = load(&obj, &LoadOptions::default()).unwrap();
    let tris: Vec<[glam::Vec3; 3]> = bunny.scene.triangles().collect();
    let mut points = String::new();
    for t in &tris {
        for p in t {
            points += &format!("({}, {}, {}), ", p.x, p.y, p.z);
        }
    }
    let counts = vec!["3"; tris.len()].join(", ");
    let indices: Vec<String> = (0..tris.len() * 3).map(|i| i.to_string()).collect();
    let mut text = format!(
        "#usda 1.0\n(\n    metersPerUnit = 1\n)\nclass Xform \"Bunny\"\n{{\n    def Mesh \"Geom\"\n    {{\n        \
         int[] faceVertexCounts = [{counts}]\n        int[] faceVertexIndices = [{}]\n        \
         point3f[] points = [{points}]\n        uniform token subdivisionScheme = \"none\"\n    }}\n}}\n",
        indices.join(", ")
    );
    for i in 0..100 {
        text += &format!(
            "def Xform \"B{i}\" (\n    instanceable = true\n    inherits = </Bunny>\n)\n{{\n    \
             double3 xformOp:translate = ({}, 0, {})\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}}\n",
            (i % 10) as f64 * 0.3,
            (i / 10) as f64 * 0.3
        );
    }
    let dir = scratch("bunnies");
    let path = dir.write("bunnies.usda", &text);
    let started = std::time::Instant::now();
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    let scene = &loaded.scene;
    println!(
        "100 bunnies: {} triangles drawn, {} stored, {} instances, geometry {:.1} MB, loaded in {:.2} s",
        scene.triangle_count(),
        scene.stored_triangle_count(),
        scene.instance_count(),
        scene.geometry_bytes() as f64 / 1e6,
        started.elapsed().as_secs_f64()
    );
    assert_eq!(scene.triangle_count(), 100 * tris.len());
    assert_eq!(scene.stored_triangle_count(), tris.len());
    assert_eq!(scene.instance_count(), 100);
    assert!(
        scene.geometry_bytes() < 40 * tris.len() * 100 / 10,
        "far under 100 copies"
    );
}

fn grid_line(name: &str, origin: [f64; 3], normal: [f64; 3]) -> String {
    format!(
        "[[grids]]\nname = \"{name}\"\norigin = {origin:?}\nu = [0.01, 0.0, 0.0]\n\
         v = [0.0, 0.0, 0.01]\nnu = 1\nnv = 1\nnormal = {normal:?}\n"
    )
}

#[test]
fn a_normalised_distant_light_gives_its_intensity_in_lux_facing_it() {
    let dir = scratch("distant");
    // Emitting along its -Z turned -60° about X: it shines from 60° above the horizon, +Z side.
    let light = "def DistantLight \"Sun\"\n{\n    float inputs:intensity = 1000\n    \
                 bool inputs:normalize = 1\n    float inputs:angle = 0.53\n    \
                 float xformOp:rotateX = -60\n    uniform token[] xformOpOrder = [\"xformOp:rotateX\"]\n}\n";
    let towards = [0.0, 60f64.to_radians().sin(), 60f64.to_radians().cos()];
    let grids = grid_line("facing", [0.0, 0.5, 0.0], towards)
        + &grid_line("floor", [0.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let results = measure_on(&dir, &floor_with(light), &grids, 20_000);
    for (g, exact) in results
        .iter()
        .zip([1000.0, 1000.0 * 60f64.to_radians().sin()])
    {
        let p = &g.points[0];
        println!(
            "{}: {:.2} ± {:.2} lx, expected {exact:.2} lx",
            g.name, p.illuminance_lx, p.std_error_lx
        );
        assert!((p.illuminance_lx / exact - 1.0).abs() < 0.005, "{}", g.name);
    }
}

#[test]
fn a_uniform_dome_light_gives_pi_l_on_the_floor() {
    let dir = scratch("dome");
    let light = "def DomeLight \"Sky\"\n{\n    float inputs:intensity = 500\n}\n";
    let grids = grid_line("floor", [0.0, 0.0, 0.0], [0.0, 1.0, 0.0])
        + &grid_line("wall", [0.0, 0.001, 0.0], [1.0, 0.0, 0.0]);
    let results = measure_on(&dir, &floor_with(light), &grids, 100_000);
    // Up: the whole sky, π L. Sideways over a black floor: the upper quarter-sphere, π L / 2.
    for (g, exact) in results.iter().zip([PI * 500.0, PI * 250.0]) {
        let p = &g.points[0];
        println!(
            "{}: {:.2} ± {:.2} lx, expected {exact:.2} lx",
            g.name, p.illuminance_lx, p.std_error_lx
        );
        assert!(
            (p.illuminance_lx / exact - 1.0).abs() < 0.01
                && (p.illuminance_lx - exact).abs() < 5.0 * p.std_error_lx,
            "{}",
            g.name
        );
    }
}

/// A latitude-longitude map dark but for a bright patch at longitude +π/2 on the horizon: in
/// OpenEXR's (and USD's) orientation that is the dome's +X.
#[test]
fn a_dome_texture_has_openexrs_orientation_and_turns_with_the_light() {
    let dir = scratch("dometex");
    let (w, h) = (64usize, 32usize);
    let map = crate::environment_input::hdr(w, h, |x, y| {
        // Longitude runs from +π at x = 0 to -π at x = w: +π/2 is at x = w / 4.
        let bright = (14..18).contains(&x) && (14..18).contains(&y);
        glam::Vec3::splat(if bright { 1000.0 } else { 0.0 })
    });
    std::fs::write(dir.0.join("patch.hdr"), map).unwrap();
    let facing = |name: &str, normal: [f64; 3]| grid_line(name, [0.0, 1.0, 0.0], normal);
    for (turn, bright_side) in [(0.0, [1.0, 0.0, 0.0]), (90.0, [0.0, 0.0, -1.0])] {
        let light = format!(
            "def DomeLight \"Sky\"\n{{\n    asset inputs:texture:file = @./patch.hdr@\n    \
             token inputs:texture:format = \"latlong\"\n    float xformOp:rotateY = {turn}\n    \
             uniform token[] xformOpOrder = [\"xformOp:rotateY\"]\n}}\n"
        );
        let opposite = bright_side.map(|c| -c);
        let grids = facing("towards", bright_side) + &facing("away", opposite);
        let r = measure_on(&dir, &floor_with(&light), &grids, 20_000);
        let (lit, dark) = (r[0].points[0].illuminance_lx, r[1].points[0].illuminance_lx);
        println!("dome turned {turn}°: {lit:.2} lx facing {bright_side:?}, {dark:.4} lx away");
        assert!(lit > 1.0 && dark < lit * 1e-3, "turned {turn}°");
    }
    // A Z-up stage: the dome's pole is the stage's up (poleAxis "scene"), its +X stays +X.
    let z_up = "#usda 1.0\n(\n    metersPerUnit = 1\n    upAxis = \"Z\"\n)\n\
                def Mesh \"Floor\"\n{\n    int[] faceVertexCounts = [4]\n    int[] faceVertexIndices = [0, 1, 2, 3]\n    \
                point3f[] points = [(-10, -10, 0), (10, -10, 0), (10, 10, 0), (-10, 10, 0)]\n    \
                color3f[] primvars:displayColor = [(0, 0, 0)]\n}\n\
                def DomeLight \"Sky\"\n{\n    asset inputs:texture:file = @./patch.hdr@\n}\n";
    let grids = facing("towards", [1.0, 0.0, 0.0]) + &facing("away", [-1.0, 0.0, 0.0]);
    let r = measure_on(&dir, z_up, &grids, 20_000);
    let (lit, dark) = (r[0].points[0].illuminance_lx, r[1].points[0].illuminance_lx);
    println!("Z-up stage: {lit:.2} lx facing +X, {dark:.4} lx away");
    assert!(lit > 1.0 && dark < lit * 1e-3, "Z up");
}

#[test]
fn ies_shaping_is_a_shape_scaled_to_the_light() {
    let dir = scratch("ies");
    let gammas: Vec<f64> = (0..=18).map(|i| f64::from(i) * 5.0).collect();
    // A cosine distribution of any absolute scale: its flux is π I0 (cosine_flux).
    let file = crate::gi_support::ies(&gammas, &[0.0], |_, g| 345.0 * g.to_radians().cos());
    std::fs::write(dir.0.join("beam.ies"), file).unwrap();
    for (normalize, expect_peak, expect_flux) in [
        (false, Some(50.0), None),
        (true, None, Some(4.0 * PI * 50.0)),
    ] {
        let light = format!(
            "def SphereLight \"Spot\" (\n    prepend apiSchemas = [\"ShapingAPI\"]\n)\n{{\n    \
             float inputs:intensity = 200\n    float inputs:radius = 0\n    bool inputs:normalize = 1\n    \
             asset inputs:shaping:ies:file = @./beam.ies@\n    bool inputs:shaping:ies:normalize = {}\n    \
             double3 xformOp:translate = (0, 2, 0)\n    float xformOp:rotateX = -90\n    \
             uniform token[] xformOpOrder = [\"xformOp:translate\", \"xformOp:rotateX\"]\n}}\n",
            u8::from(normalize)
        );
        let path = dir.write("ies.usda", &floor_with(&light));
        let d = read_scene(&path).unwrap();
        let l = &d.lights.unwrap()[0];
        // A radius-0 normalised sphere of intensity 200 is a 50 cd point: the shape's peak
        // (or flux) is taken from that.
        let tracer_core::formats::LightDistribution::Goniometric { photometry, .. } =
            &l.distribution
        else {
            panic!("{:?}", l.distribution);
        };
        assert!(
            l.aim[1] < -0.999,
            "nadir along the light's -Z, turned down: {:?}",
            l.aim
        );
        let (peak, flux) = (f64::from(photometry.max_cd()), photometry.flux_lm());
        println!("normalize {normalize}: peak {peak:.3} cd, flux {flux:.2} lm");
        if let Some(p) = expect_peak {
            assert!((peak / p - 1.0).abs() < 1e-5);
            assert!(
                (flux / (PI * p) - 1.0).abs() < 0.01,
                "a cosine's flux is π I0"
            );
        }
        if let Some(f) = expect_flux {
            assert!((flux / f - 1.0).abs() < 1e-5);
        }
    }
}

#[test]
fn time_samples_read_at_the_default_or_the_chosen_time() {
    let dir = scratch("time");
    let path = dir.write(
        "moving.usda",
        &format!(
            "#usda 1.0\n(\n    metersPerUnit = 1\n)\ndef Mesh \"M\"\n{{\n    {SQUARE}\n    \
             double3 xformOp:translate.timeSamples = {{\n        0: (0, 0, 0),\n        10: (10, 0, 0),\n    }}\n    \
             uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}}\n"
        ),
    );
    let min_x = |time: Option<f64>| {
        let options = ReadOptions {
            usd_time: time,
            ..ReadOptions::default()
        };
        let d = usd::read(&path, &options).unwrap();
        d.meshes[0]
            .positions
            .iter()
            .map(|p| p[0])
            .fold(f64::MAX, f64::min)
    };
    assert_eq!(min_x(None), 0.0, "samples only: the earliest");
    assert_eq!(min_x(Some(10.0)), 10.0);
    assert_eq!(min_x(Some(5.0)), 5.0, "linear between samples");
    assert_eq!(min_x(Some(20.0)), 10.0, "held after the last");
}

/// A UsdUVTexture on diffuseColor: a 2 x 1 PNG (red | green) on a quad whose st runs across
/// it; rendered straight on, the left half of the picture is red and the right half green.
#[test]
fn a_diffuse_texture_is_read_with_its_st() {
    let dir = scratch("texture");
    let mut png = Vec::new();
    image::RgbImage::from_fn(2, 1, |x, _| {
        if x == 0 {
            image::Rgb([255, 0, 0])
        } else {
            image::Rgb([0, 255, 0])
        }
    })
    .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
    .unwrap();
    std::fs::write(dir.0.join("two.png"), png).unwrap();
    let path = dir.write(
        "tex.usda",
        "#usda 1.0\n(\n    metersPerUnit = 1\n)\n\
         def Material \"Look\"\n{\n    token outputs:surface.connect = </Look/S.outputs:surface>\n    \
         def Shader \"S\"\n    {\n        uniform token info:id = \"UsdPreviewSurface\"\n        \
         color3f inputs:diffuseColor.connect = </Look/Tex.outputs:rgb>\n        float inputs:roughness = 1\n        token outputs:surface\n    }\n    \
         def Shader \"Tex\"\n    {\n        uniform token info:id = \"UsdUVTexture\"\n        asset inputs:file = @two.png@\n        \
         token inputs:sourceColorSpace = \"sRGB\"\n        float3 outputs:rgb\n    }\n}\n\
         def Mesh \"Quad\"\n{\n    int[] faceVertexCounts = [4]\n    int[] faceVertexIndices = [0, 1, 2, 3]\n    \
         point3f[] points = [(-1, -1, 0), (1, -1, 0), (1, 1, 0), (-1, 1, 0)]\n    \
         texCoord2f[] primvars:st = [(0, 0), (1, 0), (1, 1), (0, 1)] (\n        interpolation = \"vertex\"\n    )\n    \
         uniform token subdivisionScheme = \"none\"\n    rel material:binding = </Look>\n}\n\
         def SphereLight \"Lamp\"\n{\n    float inputs:intensity = 1000\n    float inputs:radius = 0.05\n    \
         double3 xformOp:translate = (0, 0, 3)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}\n\
         def Camera \"Cam\"\n{\n    float focalLength = 20\n    float verticalAperture = 24\n    \
         double3 xformOp:translate = (0, 0, 2)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n}\n",
    );
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    let settings = RenderSettings {
        width: 40,
        height: 20,
        samples_per_pixel: 4,
        integrator: IntegratorKind::Direct,
        ..RenderSettings::default()
    };
    let film = render(&loaded.scene, &loaded.setup, &settings).0;
    let rgb = |x: usize, y: usize| film.mean_rgb(y * 40 + x);
    // Texel centres u = 0.25 and 0.75 fall in pixels 15 and 24 (bilinear, repeat).
    let (left, right) = (rgb(15, 10), rgb(24, 10));
    println!("left {left:?}, right {right:?}");
    assert!(left[0] > 5.0 * left[1].max(1e-6), "left is red: {left:?}");
    assert!(
        right[1] > 5.0 * right[0].max(1e-6),
        "right is green: {right:?}"
    );
}

#[test]
fn a_point_instancer_places_its_prototypes_once_stored() {
    let dir = scratch("pointinstancer");
    let path = dir.write(
        "scatter.usda",
        &format!(
            "#usda 1.0\n(\n    metersPerUnit = 1\n)\n\
             def PointInstancer \"Scatter\"\n{{\n    rel prototypes = [</Scatter/Protos/Square>, </Scatter/Protos/Tall>]\n    \
             int[] protoIndices = [0, 1, 0, 1, 7]\n    \
             point3f[] positions = [(0, 0, 0), (5, 0, 0), (10, 0, 0), (15, 0, 0), (20, 0, 0)]\n    \
             quath[] orientations = [(1, 0, 0, 0), (1, 0, 0, 0), (0.7071, 0, 0.7071, 0), (1, 0, 0, 0), (1, 0, 0, 0)]\n    \
             float3[] scales = [(1, 1, 1), (1, 1, 1), (2, 2, 2), (1, 1, 1), (1, 1, 1)]\n    \
             int64[] invisibleIds = [3]\n    \
             double3 xformOp:translate = (0, 1, 0)\n    uniform token[] xformOpOrder = [\"xformOp:translate\"]\n    \
             def Scope \"Protos\"\n    {{\n        def Mesh \"Square\"\n        {{\n            {SQUARE}\n        }}\n        \
             def Xform \"Tall\"\n        {{\n            float3 xformOp:scale = (1, 3, 1)\n            \
             uniform token[] xformOpOrder = [\"xformOp:scale\"]\n            def Mesh \"Geom\"\n            {{\n                {SQUARE}\n            }}\n        }}\n    }}\n}}\n"
        ),
    );
    let d = read_scene(&path).unwrap();
    let names: Vec<&str> = d.meshes.iter().map(|m| m.name.as_str()).collect();
    println!("{names:?}\n{:#?}", d.notes);
    // Points 0, 1, 2 drawn; 3 is invisible; 4 names no prototype (noted).
    assert_eq!(
        names,
        [
            "/Scatter[0]/Square",
            "/Scatter[1]/Tall/Geom",
            "/Scatter[2]/Square"
        ]
    );
    assert!(
        d.notes
            .iter()
            .any(|n| n.contains("1 points name no prototype"))
    );
    assert_eq!(d.meshes[2].instance_of, Some(0));
    // Point 2: scaled 2, turned 90° about y, at x = 10, in the instancer's frame (y + 1): the
    // square's corner (1, 0, 0) lands at (10, 1, -2).
    let m = d.meshes[2].placement.as_ref().unwrap().world_from_local;
    let corner = m.transform_point3(DVec3::new(1.0, 0.0, 0.0));
    assert!(
        (corner - DVec3::new(10.0, 1.0, -2.0)).length() < 1e-3,
        "{corner}"
    );
    // The prototype's own transform is included: Tall's (1, 1, 0) corner is 3 high.
    let tall = &d.meshes[1];
    let m = tall.placement.as_ref().unwrap().world_from_local;
    let top = tall
        .positions
        .iter()
        .map(|p| m.transform_point3(DVec3::from(*p)).y)
        .fold(f64::MIN, f64::max);
    assert!((top - 4.0).abs() < 1e-9, "{top}");
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    assert_eq!(
        loaded.scene.stored_triangle_count(),
        4,
        "two squares stored"
    );
    assert_eq!(loaded.scene.triangle_count(), 6);
}

/// glTF's packing read from USD: roughness from `outputs:g` and metallic from `outputs:b` of
/// one image is the metallic-roughness map; a textured input's factor is 1 (the texture gives
/// the value), and opacity from an image is an alpha map.
#[test]
fn packed_roughness_metallic_and_opacity_textures_map_as_gltf_does() {
    let dir = scratch("orm");
    for name in ["orm.png", "base.png", "cut.png"] {
        let mut png = Vec::new();
        image::RgbaImage::from_pixel(2, 2, image::Rgba([200, 100, 50, 128]))
            .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
            .unwrap();
        std::fs::write(dir.0.join(name), png).unwrap();
    }
    let tex = |name: &str, file: &str| {
        format!(
            "    def Shader \"{name}\"\n    {{\n        uniform token info:id = \"UsdUVTexture\"\n        \
             asset inputs:file = @{file}@\n        float outputs:r\n        float outputs:g\n        \
             float outputs:b\n        float outputs:a\n        float3 outputs:rgb\n    }}\n"
        )
    };
    let path = dir.write(
        "orm.usda",
        &format!(
            "#usda 1.0\n(\n    metersPerUnit = 1\n)\n\
             def Material \"Look\"\n{{\n    token outputs:surface.connect = </Look/S.outputs:surface>\n    \
             def Shader \"S\"\n    {{\n        uniform token info:id = \"UsdPreviewSurface\"\n        \
             color3f inputs:diffuseColor.connect = </Look/Base.outputs:rgb>\n        \
             float inputs:roughness = 0.3\n        float inputs:roughness.connect = </Look/Orm.outputs:g>\n        \
             float inputs:metallic.connect = </Look/Orm.outputs:b>\n        \
             float inputs:opacity.connect = </Look/Cut.outputs:a>\n        float inputs:opacityThreshold = 0.5\n        \
             token outputs:surface\n    }}\n{}{}{}}}\n\
             def Mesh \"Quad\"\n{{\n    {SQUARE}\n    rel material:binding = </Look>\n}}\n",
            tex("Orm", "orm.png"),
            tex("Base", "base.png"),
            tex("Cut", "cut.png")
        ),
    );
    let d = read_scene(&path).unwrap();
    let m = &d.materials[0];
    let model = m.metal_rough.unwrap();
    assert_eq!(model.base_color, [1.0; 3], "the texture is the base colour");
    assert_eq!((model.roughness, model.metallic), (1.0, 1.0));
    let maps = m.maps.as_ref().unwrap();
    let file = |t: &Option<tracer_core::texture::TextureRef<tracer_core::formats::ImageSource>>| {
        t.as_ref().map(|t| t.texture.name())
    };
    assert!(file(&maps.metal_rough).unwrap().ends_with("orm.png"));
    assert!(file(&maps.base_color).unwrap().ends_with("base.png"));
    assert!(file(&maps.alpha_map).unwrap().ends_with("cut.png"));
    assert!(maps.roughness.is_none() && maps.metallic.is_none());
    assert_eq!(
        maps.alpha_mode,
        tracer_core::texture::AlphaMode::Mask { cutoff: 0.5 }
    );
    // The scene builds with them (images decoded).
    load(&path, &LoadOptions::default()).unwrap();
}
