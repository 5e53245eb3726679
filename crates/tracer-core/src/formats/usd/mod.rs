//! Universal Scene Description: `.usda` (text), `.usdc` (binary crate) and `.usdz` (package),
//! read with the `openusd` crate (pure Rust) and composed by it: sublayers, references,
//! payloads (all loaded), inherits, specializes, variants with their authored or default
//! selections, and scene-graph instancing.
//!
//! - Every root prim is walked (not only the default prim). Inactive prims, abstract ones
//!   (`class`), `over`s without a `def`, prims with `visibility = "invisible"` and prims of
//!   purpose `proxy` or `guide` are skipped with their subtrees: raygine draws purposes
//!   `default` and `render`.
//! - Xform op stacks ([`xform`]) accumulate down the namespace; `!resetXformStack!` restarts
//!   from the stage's frame.
//! - The stage's `metersPerUnit` (0.01 when absent, as USD says) is the scene unit;
//!   `upAxis = "Z"` turns the stage so that its +Z is raygine's +Y up.
//! - Meshes: [`mesh`]; lights: [`lights`]; materials: [`material`]; the camera: [`camera`].
//! - Instanceable prims: each prototype's meshes are read once, in the prototype's frame, and
//!   each instance places them (the scene stores their triangles once).
//! - Names: a mesh is named by its prim path (`/World/Chair`); a mesh of an instance by the
//!   instance's path and its path inside the prototype (`/World/Chair_3/Geom/Seat`). Parts are
//!   GeomSubsets, named after them. Sidecar keys are these paths.
//! - Attributes are read at their default value (an attribute with time samples only: its
//!   earliest), or at the time [`ReadOptions::usd_time`] gives (`--usd-time`).
//! - Point instancers ([`point_instancer`]): each prototype read once, each point an instance.
//! - Not drawn, and noted: subdivision (the control mesh is drawn), gprims other than meshes
//!   (Cube, Sphere, ...), points and curves.
//!
//! Any failure (a truncated or corrupt file, a missing or cyclic layer, a bad mesh) is one
//! [`FormatError`] naming the file and, where there is one, the prim path.

mod camera;
mod guard;
mod lights;
mod material;
mod mesh;
mod point_instancer;
mod values;
mod xform;

use super::error::{FormatError, check_size};
use super::{MeshDescription, ReadOptions, SceneDescription, SceneFormat};
use glam::DMat4;
use openusd::usd::{self, Prim, Stage};
use std::collections::{BTreeMap, HashMap, HashSet};
use std::path::Path;
use std::rc::Rc;
use values::Time;

/// Deepest namespace walked (real scenes are tens of levels deep).
const MAX_DEPTH: usize = 512;

/// Reads a `.usda`, `.usdc` or `.usdz` file with the layers it names.
pub fn read(path: &Path, options: &ReadOptions) -> Result<SceneDescription, FormatError> {
    let bytes = check_size(path, "the USD file")?;
    let Some(name) = path.to_str() else {
        return Err(FormatError::new(path, 0, "the file's path is not UTF-8"));
    };
    // openusd 0.6 is young: a file it trips on must not take the viewer down with it. An
    // allocation it cannot make aborts (not catchable): a child process tries the file first.
    guard::trial_read(guard::limit(options.usd_trial_secs, bytes), || {
        read_stage(path, name, options).is_ok()
    })
    .map_err(|why| FormatError::new(path, 0, why))?;
    match std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        read_stage(path, name, options)
    })) {
        Ok(result) => result,
        Err(panic) => {
            let why = panic
                .downcast_ref::<&str>()
                .map(|s| (*s).to_owned())
                .or_else(|| panic.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "no message".into());
            Err(FormatError::new(
                path,
                0,
                format!("the USD reader (openusd 0.6) failed on this file: {why}"),
            ))
        }
    }
}

fn read_stage(
    path: &Path,
    name: &str,
    options: &ReadOptions,
) -> Result<SceneDescription, FormatError> {
    let stage = usd::Stage::open(name)
        .map_err(|e| FormatError::new(path, 0, format!("not a readable USD file: {e:#}")))?;
    composition_errors(&stage, path)?;
    let metadata = |key: &str| stage.stage_metadata(key).ok().flatten();
    let metres_per_unit = metadata("metersPerUnit")
        .as_ref()
        .and_then(values::scalar)
        .unwrap_or(0.01);
    if !(metres_per_unit.is_finite() && metres_per_unit > 0.0) {
        return Err(FormatError::new(
            path,
            0,
            format!("metersPerUnit = {metres_per_unit}: must be a positive length"),
        ));
    }
    let up = metadata("upAxis")
        .as_ref()
        .and_then(values::token)
        .map_or_else(|| "Y".to_owned(), str::to_owned);
    let Some(root) = xform::up_axis(&up) else {
        return Err(FormatError::new(
            path,
            0,
            format!("upAxis = \"{up}\": USD stages are Y or Z up"),
        ));
    };
    let time = match options.usd_time {
        Some(t) if t.is_finite() => Time::At(t),
        _ => Time::Default,
    };
    let mut reader = Reader {
        stage: &stage,
        path,
        time,
        root,
        emission_scale: options.emission_scale(),
        metres_per_unit,
        is_usdz: path
            .extension()
            .is_some_and(|e| e.eq_ignore_ascii_case("usdz")),
        z_up: up == "Z",
        desc: SceneDescription {
            path: path.to_owned(),
            format: SceneFormat::Usd,
            metres_per_unit: Some(metres_per_unit as f32),
            ..SceneDescription::default()
        },
        materials: HashMap::new(),
        prototypes: HashMap::new(),
        recording: Vec::new(),
        unplaced: HashSet::new(),
        subdivided: 0,
        skipped_lights: BTreeMap::new(),
        skipped_types: BTreeMap::new(),
        hidden: 0,
        extra_cameras: 0,
    };
    let roots = stage
        .root_prims()
        .map_err(|e| FormatError::new(path, 0, format!("cannot list the root prims: {e:#}")))?;
    for token in roots {
        let prim_path = openusd::sdf::Path::new(&format!("/{}", token.as_str()))
            .map_err(|e| FormatError::new(path, 0, format!("root prim {token}: {e:#}")))?;
        let prim = stage.prim(prim_path);
        reader.prim(&prim, root, 0)?;
    }
    composition_errors(&stage, path)?;
    reader.finish()
}

/// Missing, malformed or cyclic layers and arcs: refused, naming the first few.
fn composition_errors(stage: &Stage, path: &Path) -> Result<(), FormatError> {
    let errors = stage.composition_errors();
    if errors.is_empty() {
        return Ok(());
    }
    let shown: Vec<String> = errors.iter().take(3).map(ToString::to_string).collect();
    let more = if errors.len() > 3 {
        format!(" (and {} more)", errors.len() - 3)
    } else {
        String::new()
    };
    Err(FormatError::new(
        path,
        0,
        format!("the stage does not compose: {}{more}", shown.join("; ")),
    ))
}

/// An error of the library on `prim`, as a [`FormatError`] naming it.
fn failed<'a>(path: &'a Path, prim: &'a Prim) -> impl Fn(anyhow::Error) -> FormatError + Copy + 'a {
    move |e| FormatError::new(path, 0, format!("{}: {e:#}", prim.path().as_str()))
}

/// One mesh of a prototype, as an instance places it.
#[derive(Clone)]
struct Item {
    /// The description mesh holding its triangles (in its own frame).
    mesh: usize,
    /// From that frame to the prototype's.
    frame: DMat4,
    /// Its path below the prototype's root (`/Geom/Seat`).
    relative: String,
}

/// What a prototype's walk collected.
#[derive(Clone, Default)]
struct Prototype {
    /// What it is cached under (the prototype's path, or the point instancer's target).
    key: String,
    /// The path its meshes' names are taken relative to.
    root: String,
    items: Vec<Item>,
    /// Point lights in the prototype's frame.
    lights: Vec<super::LightDescription>,
}

/// The walk over a composed stage.
pub(super) struct Reader<'r> {
    stage: &'r Stage,
    path: &'r Path,
    time: Time,
    /// The stage's frame in raygine's (the up-axis turn).
    root: DMat4,
    emission_scale: f32,
    metres_per_unit: f64,
    is_usdz: bool,
    /// The stage is Z up.
    z_up: bool,
    desc: SceneDescription,
    /// Material prim path (or displayColor key) to description index (None: not drawn).
    materials: HashMap<String, Option<usize>>,
    /// Prototype key to what it holds, once walked.
    prototypes: HashMap<String, Rc<Prototype>>,
    /// The prototypes being walked, innermost last.
    recording: Vec<Prototype>,
    /// Prototype meshes no instance has placed yet (the first placement takes the mesh itself).
    unplaced: HashSet<usize>,
    subdivided: usize,
    skipped_lights: BTreeMap<String, usize>,
    skipped_types: BTreeMap<String, usize>,
    hidden: usize,
    extra_cameras: usize,
}

impl Reader<'_> {
    /// "file: /prim/path", for notes.
    fn at(&self, prim: &Prim) -> String {
        format!("{}: {}", self.path.display(), prim.path().as_str())
    }

    fn error_at(&self, prim: &Prim, why: String) -> FormatError {
        FormatError::new(self.path, 0, format!("{}: {why}", prim.path().as_str()))
    }

    /// The bytes of a file inside the `.usdz` being read (a texture).
    fn package_bytes(&self, file: &str) -> Result<Vec<u8>, String> {
        use openusd::ar::Resolver;
        let name = format!("{}[{}]", self.path.display(), file.trim_start_matches("./"));
        openusd::ar::DefaultResolver::new()
            .open_asset(&openusd::ar::ResolvedPath::new(&name))
            .and_then(|mut a| a.read_all())
            .map_err(|e| e.to_string())
    }

    fn prim(&mut self, prim: &Prim, parent: DMat4, depth: usize) -> Result<(), FormatError> {
        if depth > MAX_DEPTH {
            return Err(self.error_at(
                prim,
                format!("the namespace is deeper than {MAX_DEPTH} levels"),
            ));
        }
        let fails = failed(self.path, prim);
        // openusd 0.6 reports the prims of a prototype composed from a `class` as abstract:
        // inside a prototype, only activity and definition count.
        let abstract_prim = self.recording.is_empty() && prim.is_abstract().map_err(fails)?;
        if !prim.is_active().map_err(fails)?
            || abstract_prim
            || !prim.is_defined().map_err(fails)?
        {
            return Ok(());
        }
        let kind = prim
            .type_name()
            .map_err(fails)?
            .map(|t| t.as_str().to_owned())
            .unwrap_or_default();
        if matches!(
            kind.as_str(),
            "Material" | "Shader" | "NodeGraph" | "GeomSubset"
        ) {
            return Ok(());
        }
        let visibility =
            values::attr_token(prim, "visibility").map_err(|e| self.error_at(prim, e))?;
        let purpose = values::attr_token(prim, "purpose").map_err(|e| self.error_at(prim, e))?;
        if visibility.as_deref() == Some("invisible")
            || matches!(purpose.as_deref(), Some("proxy" | "guide"))
        {
            self.hidden += 1;
            return Ok(());
        }
        let (local, reset) = xform::local(prim, self.time).map_err(|e| self.error_at(prim, e))?;
        let base = if reset {
            if self.recording.is_empty() {
                self.root
            } else {
                DMat4::IDENTITY
            }
        } else {
            parent
        };
        let world = base * local;
        if prim.is_instance().map_err(fails)? {
            return self.instance(prim, world, depth);
        }
        if kind == "PointInstancer" {
            // What is below it is drawn through it only.
            return self.point_instancer(prim, world, depth);
        }
        match kind.as_str() {
            "Mesh" => {
                let name = prim.path().as_str().to_owned();
                if let Some(mesh) = self.mesh(prim, world, name)? {
                    self.push_mesh(mesh);
                }
            }
            "Camera" => {
                if self.recording.is_empty() {
                    self.camera(prim, world);
                }
            }
            k if lights::LIGHT_TYPES.contains(&k) => {
                let before = self.desc.meshes.len();
                self.light(prim, k, world)?;
                // An area light inside a prototype is one of its meshes.
                for i in before..self.desc.meshes.len() {
                    self.record(i);
                }
            }
            "" | "Xform" | "Scope" | "SkelRoot" => {}
            other => {
                *self.skipped_types.entry(other.to_owned()).or_insert(0) += 1;
            }
        }
        for child in prim.children().map_err(fails)? {
            self.prim(&child, world, depth + 1)?;
        }
        Ok(())
    }

    fn push_mesh(&mut self, mesh: MeshDescription) {
        self.desc.meshes.push(mesh);
        self.record(self.desc.meshes.len() - 1);
    }

    /// Inside a prototype's walk, a mesh belongs to the prototype (placed by its instances).
    fn record(&mut self, mesh: usize) {
        if let Some(proto) = self.recording.last_mut() {
            let relative = self.desc.meshes[mesh]
                .name
                .strip_prefix(&proto.root)
                .unwrap_or_default()
                .to_owned();
            proto.items.push(Item {
                mesh,
                frame: DMat4::IDENTITY,
                relative,
            });
            self.unplaced.insert(mesh);
        }
    }

    /// An instance: its prototype walked once, then placed by `world`.
    fn instance(&mut self, prim: &Prim, world: DMat4, depth: usize) -> Result<(), FormatError> {
        let fails = failed(self.path, prim);
        let Some(proto_path) = prim.prototype().map_err(fails)? else {
            return Ok(());
        };
        let key = proto_path.as_str().to_owned();
        let proto = self.prototype(&key, &key, prim, |reader| {
            let root = reader.stage.prim(proto_path.clone());
            for child in root.children().map_err(fails)? {
                reader.prim(&child, DMat4::IDENTITY, depth + 1)?;
            }
            Ok(())
        })?;
        self.place(&proto, world, prim.path().as_str());
        Ok(())
    }

    /// The prototype cached under `key`, walked by `walk` the first time (its meshes named
    /// relative to `root`). `prim` names the instance in errors.
    fn prototype(
        &mut self,
        key: &str,
        root: &str,
        prim: &Prim,
        walk: impl FnOnce(&mut Self) -> Result<(), FormatError>,
    ) -> Result<Rc<Prototype>, FormatError> {
        if let Some(known) = self.prototypes.get(key) {
            return Ok(Rc::clone(known));
        }
        if self.recording.iter().any(|p| p.key == key) {
            return Err(self.error_at(prim, format!("instancing cycle through {key}")));
        }
        self.recording.push(Prototype {
            key: key.to_owned(),
            root: root.to_owned(),
            ..Prototype::default()
        });
        let lights_before = self.desc.lights.as_ref().map_or(0, Vec::len);
        let walked = walk(self);
        let mut recorded = self.recording.pop().unwrap_or_default();
        walked?;
        if let Some(lights) = &mut self.desc.lights {
            recorded.lights = lights.split_off(lights_before.min(lights.len()));
        }
        let recorded = Rc::new(recorded);
        self.prototypes.insert(key.to_owned(), Rc::clone(&recorded));
        Ok(recorded)
    }

    /// Places `proto`'s meshes and lights by `world` as the instance `instance_path` (inside
    /// another prototype's walk: as items of that one, placed when it is).
    fn place(&mut self, proto: &Prototype, world: DMat4, instance_path: &str) {
        for item in &proto.items {
            let placement = world * item.frame;
            let name = format!("{instance_path}{}", item.relative);
            if let Some(outer) = self.recording.last_mut() {
                let relative = name
                    .strip_prefix(&outer.root)
                    .unwrap_or_default()
                    .to_owned();
                outer.items.push(Item {
                    mesh: item.mesh,
                    frame: placement,
                    relative,
                });
                continue;
            }
            let placement = Some(super::PlacementDescription {
                world_from_local: placement,
                source: self.path.to_owned(),
                line: 0,
            });
            if self.unplaced.remove(&item.mesh) {
                let mesh = &mut self.desc.meshes[item.mesh];
                mesh.name = name;
                mesh.placement = placement;
            } else {
                let parts = self.desc.meshes[item.mesh].parts.clone();
                self.desc.meshes.push(MeshDescription {
                    name,
                    source: self.path.to_owned(),
                    parts,
                    placement,
                    instance_of: Some(item.mesh),
                    ..MeshDescription::default()
                });
            }
        }
        for light in &proto.lights {
            let mut light = light.clone();
            let to = |p: [f32; 3], point: bool| {
                let v = glam::DVec3::from(p.map(f64::from));
                let w = if point {
                    world.transform_point3(v)
                } else {
                    world.transform_vector3(v)
                };
                w.as_vec3().to_array()
            };
            light.position = to(light.position, true);
            light.aim = to(light.aim, false);
            light.name = format!(
                "{instance_path}{}",
                light.name.strip_prefix(&proto.root).unwrap_or_default()
            );
            match self.recording.last_mut() {
                Some(outer) => outer.lights.push(light),
                None => self.desc.lights.get_or_insert_with(Vec::new).push(light),
            }
        }
    }

    /// The notes the walk collected, and the final checks.
    fn finish(mut self) -> Result<SceneDescription, FormatError> {
        let file = self.path.display().to_string();
        if self.subdivided > 0 {
            self.desc.notes.push(format!(
                "{file}: {} meshes are subdivision surfaces (USD's default scheme, catmullClark, \
                 unless subdivisionScheme = \"none\"); their control meshes are drawn, \
                 triangulated",
                self.subdivided
            ));
        }
        for (kind, n) in &self.skipped_lights {
            self.desc
                .notes
                .push(format!("{file}: {n} {kind}s are not drawn yet"));
        }
        if !self.skipped_types.is_empty() {
            let list: Vec<String> = self
                .skipped_types
                .iter()
                .map(|(k, n)| format!("{n} {k}"))
                .collect();
            self.desc.notes.push(format!(
                "{file}: prims raygine does not draw: {} (meshes only)",
                list.join(", ")
            ));
        }
        if self.hidden > 0 {
            self.desc.notes.push(format!(
                "{file}: {} invisible, proxy or guide prims skipped (with what is below them)",
                self.hidden
            ));
        }
        if self.extra_cameras > 0 {
            self.desc.notes.push(format!(
                "{file}: {} more cameras; the first one is used",
                self.extra_cameras
            ));
        }
        if self
            .desc
            .meshes
            .iter()
            .all(|m| m.triangles.is_empty() && m.instance_of.is_none())
        {
            return Err(FormatError::new(self.path, 0, "no meshes: nothing to draw"));
        }
        Ok(self.desc)
    }
}
