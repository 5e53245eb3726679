//! The few Embree 3 C entry points the benchmark needs, declared by hand against the 3.13
//! headers (`/usr/include/embree3/rtcore_*.h`, Debian's libembree-dev); links `libembree3`.
//! Layouts follow those headers with `RTC_MAX_INSTANCE_LEVEL_COUNT == 1` and `RTC_MIN_WIDTH == 0`,
//! as Debian builds it.

use std::ffi::{c_char, c_uint, c_void};

pub type RtcDevice = *mut c_void;
pub type RtcScene = *mut c_void;
pub type RtcGeometry = *mut c_void;

pub const RTC_GEOMETRY_TYPE_TRIANGLE: c_uint = 0;
pub const RTC_BUFFER_TYPE_INDEX: c_uint = 0;
pub const RTC_BUFFER_TYPE_VERTEX: c_uint = 1;
pub const RTC_FORMAT_UINT3: c_uint = 0x5003;
pub const RTC_FORMAT_FLOAT3: c_uint = 0x9003;
pub const RTC_BUILD_QUALITY_HIGH: c_uint = 2;
pub const RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT: c_uint = 0;
pub const RTC_INVALID_GEOMETRY_ID: c_uint = u32::MAX;
pub const RTC_ERROR_NONE: c_uint = 0;

/// `struct RTCRay` (16-byte aligned, 48 bytes).
#[repr(C, align(16))]
#[derive(Clone, Copy, Debug, Default)]
pub struct RtcRay {
    pub org: [f32; 3],
    pub tnear: f32,
    pub dir: [f32; 3],
    pub time: f32,
    pub tfar: f32,
    pub mask: c_uint,
    pub id: c_uint,
    pub flags: c_uint,
}

/// `struct RTCHit` (16-byte aligned, 32 bytes).
#[repr(C, align(16))]
#[derive(Clone, Copy, Debug, Default)]
pub struct RtcHit {
    pub ng: [f32; 3],
    pub u: f32,
    pub v: f32,
    pub prim_id: c_uint,
    pub geom_id: c_uint,
    pub inst_id: [c_uint; 1],
}

/// `struct RTCRayHit`.
#[repr(C, align(16))]
#[derive(Clone, Copy, Debug, Default)]
pub struct RtcRayHit {
    pub ray: RtcRay,
    pub hit: RtcHit,
}

/// `struct RTCIntersectContext`: flags, filter function, instance id stack of one.
#[repr(C)]
#[derive(Clone, Copy, Debug)]
pub struct RtcIntersectContext {
    pub flags: c_uint,
    pub filter: *const c_void,
    pub inst_id: [c_uint; 1],
}

impl RtcIntersectContext {
    /// What the header's inline `rtcInitIntersectContext` does (it is not exported).
    pub fn new() -> Self {
        Self {
            flags: RTC_INTERSECT_CONTEXT_FLAG_INCOHERENT,
            filter: std::ptr::null(),
            inst_id: [RTC_INVALID_GEOMETRY_ID],
        }
    }
}

#[link(name = "embree3")]
unsafe extern "C" {
    pub fn rtcNewDevice(config: *const c_char) -> RtcDevice;
    pub fn rtcReleaseDevice(device: RtcDevice);
    pub fn rtcGetDeviceError(device: RtcDevice) -> c_uint;
    pub fn rtcNewScene(device: RtcDevice) -> RtcScene;
    pub fn rtcSetSceneBuildQuality(scene: RtcScene, quality: c_uint);
    pub fn rtcNewGeometry(device: RtcDevice, kind: c_uint) -> RtcGeometry;
    pub fn rtcSetGeometryBuildQuality(geometry: RtcGeometry, quality: c_uint);
    pub fn rtcSetNewGeometryBuffer(
        geometry: RtcGeometry,
        kind: c_uint,
        slot: c_uint,
        format: c_uint,
        byte_stride: usize,
        item_count: usize,
    ) -> *mut c_void;
    pub fn rtcCommitGeometry(geometry: RtcGeometry);
    pub fn rtcAttachGeometry(scene: RtcScene, geometry: RtcGeometry) -> c_uint;
    pub fn rtcReleaseGeometry(geometry: RtcGeometry);
    pub fn rtcCommitScene(scene: RtcScene);
    pub fn rtcReleaseScene(scene: RtcScene);
    pub fn rtcIntersect1(
        scene: RtcScene,
        context: *mut RtcIntersectContext,
        rayhit: *mut RtcRayHit,
    );
    pub fn rtcOccluded1(scene: RtcScene, context: *mut RtcIntersectContext, ray: *mut RtcRay);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layouts_match_the_headers() {
        assert_eq!(size_of::<RtcRay>(), 48);
        assert_eq!(size_of::<RtcHit>(), 32);
        assert_eq!(size_of::<RtcRayHit>(), 80);
        assert_eq!(size_of::<RtcIntersectContext>(), 24);
    }
}
