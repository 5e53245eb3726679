//! `.lgt` luminaires, read as written: `Light` (what a lamp emits), `Fixture` (a placed,
//! switched light), `Group` (fixtures switched and dimmed together) and `Diagram` (intensity
//! tables) blocks, and the first `Geography` (place, time and orientation for the sun). Other
//! blocks are skipped. The mapping to lights is in `luminaires.rs`, to `[daylight]` in
//! [`Geography::to_daylight`].

use super::error::IntegraError;
use super::lines::{self, Block, Line, numbers, switch, word};
use std::path::Path;

/// Largest `theta` × `phi` of a diagram (values are read from the text, so this only bounds
/// what a table may claim).
pub const MAX_DIAGRAM_VALUES: u64 = 4_000_000;

/// A name a block refers to, with the line it is written on.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Reference {
    pub name: String,
    pub line: usize,
}

/// A `.lgt` file as written.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Lgt {
    pub lights: Vec<LgtLight>,
    pub fixtures: Vec<Fixture>,
    pub groups: Vec<Group>,
    pub diagrams: Vec<Diagram>,
    /// The first `Geography` block.
    pub geography: Option<Geography>,
    /// Blocks not read (keyword, name, line).
    pub skipped: Vec<(String, String, usize)>,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct LgtLight {
    pub name: String,
    pub line: usize,
    /// `type` as written (`point`).
    pub kind: Option<Reference>,
    /// `TotalFlux`, lm.
    pub total_flux: Option<f64>,
    /// `intensity R G B`: a colour tint.
    pub intensity: Option<[f64; 3]>,
    /// `SpotLight on|off`, with its line.
    pub spot: Option<(bool, usize)>,
    /// `Diagram NAME`: the intensity table this light uses.
    pub diagram: Option<Reference>,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Fixture {
    pub name: String,
    pub line: usize,
    pub light: Option<Reference>,
    pub switch: Option<bool>,
    pub position: Option<[f64; 3]>,
    /// The aim (the table's θ = 0).
    pub direction: Option<[f64; 3]>,
    /// Turn about the aim, degrees.
    pub rotation: Option<f64>,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Group {
    pub name: String,
    pub line: usize,
    pub switch: Option<bool>,
    /// `Power P%`.
    pub power_percent: Option<f64>,
    /// The fixtures listed after `def`.
    pub members: Vec<Reference>,
}

#[derive(Clone, Debug, Default, PartialEq)]
pub struct Diagram {
    pub name: String,
    pub line: usize,
    /// `type` as written (`AxiSymmetrical`).
    pub kind: Option<String>,
    /// Number of θ angles, spanning 0–180° in `theta − 1` steps.
    pub theta: Option<u32>,
    /// Number of φ planes.
    pub phi: Option<u32>,
    /// The flux the table stands for, lm (the table does not integrate to it).
    pub normal_flux: Option<f64>,
    /// The values after `def`, cd.
    pub values: Vec<f64>,
    /// `diagrams N`: a composed diagram of N tables (not read further).
    pub composed: Option<u32>,
}

/// Reads a `.lgt` file's bytes (`path` only names it in messages).
pub fn parse_lgt(bytes: &[u8], path: &Path) -> Result<Lgt, IntegraError> {
    let text = lines::decode(bytes, path)?;
    let mut lgt = Lgt::default();
    let mut names: Vec<(String, String, usize)> = Vec::new();
    for block in lines::blocks(lines::lines(&text), path, ".lgt")? {
        let keyword = block.keyword.to_ascii_lowercase();
        if ["light", "fixture", "group", "diagram"].contains(&keyword.as_str()) {
            if let Some((_, _, first)) = names
                .iter()
                .find(|(k, n, _)| *k == keyword && n == block.name)
            {
                return Err(IntegraError::new(
                    path,
                    block.line,
                    format!(
                        "{} {} is defined twice (first at line {first})",
                        block.keyword, block.name
                    ),
                ));
            }
            names.push((keyword.clone(), block.name.to_owned(), block.line));
        }
        match keyword.as_str() {
            "light" => lgt.lights.push(light(&block, path)?),
            "fixture" => lgt.fixtures.push(fixture(&block, path)?),
            "group" => lgt.groups.push(group(&block, path)?),
            "diagram" => lgt.diagrams.push(diagram(&block, path)?),
            "geography" if lgt.geography.is_none() => {
                lgt.geography = Some(geography(&block, path)?);
            }
            _ => lgt
                .skipped
                .push((block.keyword.to_owned(), block.name.to_owned(), block.line)),
        }
    }
    Ok(lgt)
}

/// A `Geography` block: where and when, for the sun.
///
/// ```text
/// Geography TokyoMidday
///   zenith    0.0000 1.0000 0.0000
///   south     1.0000 0.0000 0.0000
///   latitude  36.0
///   longitude -140.0          (west positive, as Radiance counts)
///   month     6
///   date      21
///   time      12:00
///   GMT       9
///   DaylightSaving off
/// enddef
/// ```
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Geography {
    pub name: String,
    pub line: usize,
    pub zenith: Option<[f64; 3]>,
    pub south: Option<[f64; 3]>,
    pub latitude: Option<f64>,
    /// West positive.
    pub longitude: Option<f64>,
    pub month: Option<f64>,
    pub date: Option<f64>,
    pub time: Option<String>,
    pub gmt: Option<f64>,
    pub daylight_saving: Option<bool>,
}

/// The year a `Geography` date is taken in: Integra gives month and day only.
pub const GEOGRAPHY_YEAR: i32 = 2025;

impl Geography {
    /// The sidecar's `[daylight]` this block means (the year [`GEOGRAPHY_YEAR`]; north is
    /// −south); None with a note when a key it needs is missing.
    pub fn to_daylight(
        &self,
        path: &Path,
        notes: &mut Vec<String>,
    ) -> Option<crate::light::daylight::DaylightSpec> {
        let missing: Vec<&str> = [
            ("latitude", self.latitude.is_none()),
            ("longitude", self.longitude.is_none()),
            ("month", self.month.is_none()),
            ("date", self.date.is_none()),
            ("time", self.time.is_none()),
            ("GMT", self.gmt.is_none()),
        ]
        .iter()
        .filter_map(|&(k, m)| m.then_some(k))
        .collect();
        if !missing.is_empty() {
            notes.push(format!(
                "{}:{}: Geography {} has no {}; no daylight",
                path.display(),
                self.line,
                self.name,
                missing.join(", ")
            ));
            return None;
        }
        let f = |v: Option<[f64; 3]>| v.map(|v| v.map(|c| c as f32));
        Some(crate::light::daylight::DaylightSpec {
            latitude: self.latitude.unwrap_or_default(),
            longitude: self.longitude.unwrap_or_default(),
            longitude_convention: Some("west".to_owned()),
            date: format!(
                "{GEOGRAPHY_YEAR}-{:02}-{:02}",
                self.month.unwrap_or_default() as u32,
                self.date.unwrap_or_default() as u32
            ),
            time: self.time.clone().unwrap_or_default(),
            timezone: self.gmt.unwrap_or_default(),
            daylight_saving: self.daylight_saving.unwrap_or(false),
            north: f(self.south).map(|s| s.map(|c| -c)),
            zenith: f(self.zenith),
            sky: None,
            zenith_luminance_cd_m2: None,
            diffuse_horizontal_lx: None,
            ground_reflectance: None,
            direct_normal_lx: None,
            sun: false,
            sun_normal_illuminance_lx: None,
        })
    }
}

fn geography(block: &Block, path: &Path) -> Result<Geography, IntegraError> {
    let mut g = Geography {
        name: block.name.to_owned(),
        line: block.line,
        ..Geography::default()
    };
    for line in &block.body {
        match line.key().to_ascii_lowercase().as_str() {
            "zenith" => g.zenith = Some(numbers::<3>(path, line)?),
            "south" => g.south = Some(numbers::<3>(path, line)?),
            "latitude" => g.latitude = Some(numbers::<1>(path, line)?[0]),
            "longitude" => g.longitude = Some(numbers::<1>(path, line)?[0]),
            "month" => g.month = Some(numbers::<1>(path, line)?[0]),
            "date" => g.date = Some(numbers::<1>(path, line)?[0]),
            "time" => g.time = Some(word(path, line)?.to_owned()),
            "gmt" => g.gmt = Some(numbers::<1>(path, line)?[0]),
            "daylightsaving" => g.daylight_saving = Some(switch(path, line)?),
            _ => {}
        }
    }
    Ok(g)
}

fn reference(path: &Path, line: &Line) -> Result<Reference, IntegraError> {
    Ok(Reference {
        name: word(path, line)?.to_owned(),
        line: line.no,
    })
}

fn light(block: &Block, path: &Path) -> Result<LgtLight, IntegraError> {
    let mut l = LgtLight {
        name: block.name.to_owned(),
        line: block.line,
        ..LgtLight::default()
    };
    for line in &block.body {
        match line.key().to_ascii_lowercase().as_str() {
            "type" => l.kind = Some(reference(path, line)?),
            "totalflux" => l.total_flux = Some(numbers::<1>(path, line)?[0]),
            "intensity" => l.intensity = Some(numbers::<3>(path, line)?),
            "spotlight" => l.spot = Some((switch(path, line)?, line.no)),
            "diagram" => l.diagram = Some(reference(path, line)?),
            _ => {}
        }
    }
    Ok(l)
}

fn fixture(block: &Block, path: &Path) -> Result<Fixture, IntegraError> {
    let mut f = Fixture {
        name: block.name.to_owned(),
        line: block.line,
        ..Fixture::default()
    };
    for line in &block.body {
        match line.key().to_ascii_lowercase().as_str() {
            "light" => f.light = Some(reference(path, line)?),
            "switch" => f.switch = Some(switch(path, line)?),
            "position" => f.position = Some(numbers::<3>(path, line)?),
            "direction" => f.direction = Some(numbers::<3>(path, line)?),
            "rotation" => f.rotation = Some(numbers::<1>(path, line)?[0]),
            _ => {}
        }
    }
    Ok(f)
}

fn group(block: &Block, path: &Path) -> Result<Group, IntegraError> {
    let mut g = Group {
        name: block.name.to_owned(),
        line: block.line,
        ..Group::default()
    };
    let mut in_def = false;
    for line in &block.body {
        if in_def {
            g.members.push(Reference {
                name: line.words.join(" "),
                line: line.no,
            });
            continue;
        }
        match line.key().to_ascii_lowercase().as_str() {
            "switch" => g.switch = Some(switch(path, line)?),
            "power" => {
                let w = word(path, line)?;
                let p = lines::number(path, line.no, w.trim_end_matches('%'), "Power")?;
                if !(0.0..=1000.0).contains(&p) {
                    return Err(IntegraError::new(
                        path,
                        line.no,
                        format!("`Power` is a percentage from 0 to 1000, found {p}"),
                    ));
                }
                g.power_percent = Some(p);
            }
            "def" => in_def = true,
            _ => {}
        }
    }
    Ok(g)
}

fn count(path: &Path, line: &Line) -> Result<u32, IntegraError> {
    let [n] = numbers::<1>(path, line)?;
    if n.fract() != 0.0 || !(1.0..=f64::from(u32::MAX)).contains(&n) {
        return Err(IntegraError::new(
            path,
            line.no,
            format!("`{}` is a whole number from 1, found {n}", line.key()),
        ));
    }
    Ok(n as u32)
}

fn diagram(block: &Block, path: &Path) -> Result<Diagram, IntegraError> {
    let mut d = Diagram {
        name: block.name.to_owned(),
        line: block.line,
        ..Diagram::default()
    };
    let mut def_line = None;
    for line in &block.body {
        if def_line.is_some() && line.key().parse::<f64>().is_ok() {
            for w in &line.words {
                d.values
                    .push(lines::number(path, line.no, w, "diagram value")?);
            }
            continue;
        }
        def_line = None;
        match line.key().to_ascii_lowercase().as_str() {
            "type" => d.kind = Some(word(path, line)?.to_owned()),
            "theta" => d.theta = Some(count(path, line)?),
            "phi" => d.phi = Some(count(path, line)?),
            "normalflux" => d.normal_flux = Some(numbers::<1>(path, line)?[0]),
            "diagrams" => {
                // A composed diagram: several tables by angle. Kept as a count only.
                d.composed = Some(count(path, line)?);
                return Ok(d);
            }
            "def" => {
                if !d.values.is_empty() {
                    return Err(IntegraError::new(
                        path,
                        line.no,
                        format!("diagram {} has a second `def`", d.name),
                    ));
                }
                def_line = Some(line.no);
            }
            _ => {}
        }
    }
    let expected = u64::from(d.theta.unwrap_or(0)) * u64::from(d.phi.unwrap_or(1));
    if expected > MAX_DIAGRAM_VALUES {
        return Err(IntegraError::new(
            path,
            block.line,
            format!(
                "diagram {}: theta × phi = {expected} values, more than {MAX_DIAGRAM_VALUES}",
                d.name
            ),
        ));
    }
    if d.theta.is_some() && d.values.len() as u64 != expected {
        return Err(IntegraError::new(
            path,
            block.line,
            format!(
                "diagram {}: theta × phi = {expected} values expected after `def`, found {}",
                d.name,
                d.values.len()
            ),
        ));
    }
    Ok(d)
}
