//! Intel Embree 3 (the system's libembree3): one triangle geometry, build quality high, single-ray
//! `rtcIntersect1` / `rtcOccluded1`. The device gets `threads=N` so the build uses the same number
//! of threads as the others; tracing runs on the benchmark's rayon pool like every library.
//! A device is made once per thread count and kept while that count is measured (starting
//! Embree's task system is not part of a BVH build); the timed build is buffers +
//! `rtcCommitScene`. Only one device lives at a time: Embree sizes its task system for the
//! largest `threads=` of all live devices, so a 2-thread device left alive made "1-thread"
//! builds use 2 threads (seen: ogre 118 ms at both counts, 214 ms with the 1-thread device
//! alone).

use std::ffi::CString;
use std::sync::{Arc, Mutex};

use anyhow::{bail, ensure};
use glam::Vec3;
use tracer_core::Ray;

use super::Accel;
use super::embree_ffi as ffi;

/// An Embree device configured for a number of threads.
#[derive(Debug)]
struct Device(ffi::RtcDevice);

// SAFETY: Embree devices are thread-safe objects; the handle is only released in `Drop`.
unsafe impl Send for Device {}
// SAFETY: as above.
unsafe impl Sync for Device {}

impl Drop for Device {
    fn drop(&mut self) {
        // SAFETY: the handle came from rtcNewDevice and is released exactly once.
        unsafe { ffi::rtcReleaseDevice(self.0) };
    }
}

/// The live device and its thread count (at most one; see the module docs).
static DEVICES: Mutex<Vec<(usize, Arc<Device>)>> = Mutex::new(Vec::new());

fn device(threads: usize) -> anyhow::Result<Arc<Device>> {
    let mut devices = DEVICES.lock().unwrap_or_else(|e| e.into_inner());
    if let Some((_, d)) = devices.iter().find(|(n, _)| *n == threads) {
        return Ok(Arc::clone(d));
    }
    // Release the device of another count first (scenes are cleared between counts, so this
    // was the last reference).
    devices.clear();
    let config = CString::new(format!("threads={threads}"))?;
    // SAFETY: a valid NUL-terminated configuration string.
    let handle = unsafe { ffi::rtcNewDevice(config.as_ptr()) };
    ensure!(!handle.is_null(), "rtcNewDevice failed");
    let d = Arc::new(Device(handle));
    devices.push((threads, Arc::clone(&d)));
    Ok(d)
}

/// A committed Embree scene and the device that owns it.
#[derive(Debug)]
pub struct Embree {
    scene: ffi::RtcScene,
    /// Keeps the device alive as long as the scene.
    _device: Arc<Device>,
}

// SAFETY: Embree documents rtcIntersect1/rtcOccluded1 on a committed scene as thread-safe, and
// the handle is never mutated after `build`; release happens once, in `Drop`.
unsafe impl Send for Embree {}
// SAFETY: as above: shared references only ever issue thread-safe queries.
unsafe impl Sync for Embree {}

impl Drop for Embree {
    fn drop(&mut self) {
        // SAFETY: the scene came from rtcNewScene in `build` and is released exactly once.
        unsafe { ffi::rtcReleaseScene(self.scene) };
    }
}

fn ray_of(ray: &Ray) -> ffi::RtcRay {
    ffi::RtcRay {
        org: ray.origin.to_array(),
        tnear: ray.t_min,
        dir: ray.dir.to_array(),
        time: 0.0,
        tfar: ray.t_max,
        mask: u32::MAX,
        id: 0,
        flags: 0,
    }
}

impl Accel for Embree {
    const NAME: &'static str = "embree";

    fn build(triangles: &[[Vec3; 3]], threads: usize) -> anyhow::Result<Self> {
        let device = device(threads)?;
        // SAFETY: plain C calls with valid arguments; every returned handle is checked for null,
        // and the buffers Embree allocates are written within the item counts given to it.
        unsafe {
            let scene = ffi::rtcNewScene(device.0);
            ensure!(!scene.is_null(), "rtcNewScene failed");
            let embree = Embree {
                scene,
                _device: Arc::clone(&device),
            };
            ffi::rtcSetSceneBuildQuality(scene, ffi::RTC_BUILD_QUALITY_HIGH);
            let geometry = ffi::rtcNewGeometry(device.0, ffi::RTC_GEOMETRY_TYPE_TRIANGLE);
            ensure!(!geometry.is_null(), "rtcNewGeometry failed");
            ffi::rtcSetGeometryBuildQuality(geometry, ffi::RTC_BUILD_QUALITY_HIGH);
            let n = triangles.len();
            let vertices = ffi::rtcSetNewGeometryBuffer(
                geometry,
                ffi::RTC_BUFFER_TYPE_VERTEX,
                0,
                ffi::RTC_FORMAT_FLOAT3,
                3 * size_of::<f32>(),
                3 * n,
            )
            .cast::<[f32; 3]>();
            let indices = ffi::rtcSetNewGeometryBuffer(
                geometry,
                ffi::RTC_BUFFER_TYPE_INDEX,
                0,
                ffi::RTC_FORMAT_UINT3,
                3 * size_of::<u32>(),
                n,
            )
            .cast::<[u32; 3]>();
            ensure!(
                !vertices.is_null() && !indices.is_null(),
                "rtcSetNewGeometryBuffer failed"
            );
            let vertices = std::slice::from_raw_parts_mut(vertices, 3 * n);
            let indices = std::slice::from_raw_parts_mut(indices, n);
            for (i, tri) in triangles.iter().enumerate() {
                for (k, v) in tri.iter().enumerate() {
                    vertices[3 * i + k] = v.to_array();
                }
                let base = 3 * i as u32;
                indices[i] = [base, base + 1, base + 2];
            }
            ffi::rtcCommitGeometry(geometry);
            ffi::rtcAttachGeometry(scene, geometry);
            ffi::rtcReleaseGeometry(geometry);
            ffi::rtcCommitScene(scene);
            let error = ffi::rtcGetDeviceError(device.0);
            if error != ffi::RTC_ERROR_NONE {
                bail!("Embree reported error {error} while building");
            }
            Ok(embree)
        }
    }

    fn closest(&self, ray: &Ray) -> Option<(f32, u32)> {
        let mut context = ffi::RtcIntersectContext::new();
        let mut rayhit = ffi::RtcRayHit {
            ray: ray_of(ray),
            hit: ffi::RtcHit {
                geom_id: ffi::RTC_INVALID_GEOMETRY_ID,
                inst_id: [ffi::RTC_INVALID_GEOMETRY_ID],
                ..ffi::RtcHit::default()
            },
        };
        // SAFETY: the scene is committed; context and rayhit are valid, aligned and exclusive.
        unsafe { ffi::rtcIntersect1(self.scene, &mut context, &mut rayhit) };
        (rayhit.hit.geom_id != ffi::RTC_INVALID_GEOMETRY_ID)
            .then_some((rayhit.ray.tfar, rayhit.hit.prim_id))
    }

    fn occluded(&self, ray: &Ray) -> bool {
        let mut context = ffi::RtcIntersectContext::new();
        let mut r = ray_of(ray);
        // SAFETY: as in `closest`.
        unsafe { ffi::rtcOccluded1(self.scene, &mut context, &mut r) };
        // Embree marks an occluded ray by setting tfar to -inf.
        r.tfar == f32::NEG_INFINITY
    }
}
