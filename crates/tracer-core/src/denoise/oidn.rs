//! The Open Image Denoise 2.x C API, loaded at run time: the few entry points raygine calls, as
//! function pointers kept beside the library that owns them. Building raygine never needs OIDN.

use std::ffi::{CStr, CString, c_char, c_int, c_void};

type Device = *mut c_void;
type Filter = *mut c_void;

/// `OIDN_DEVICE_TYPE_CPU`.
const DEVICE_TYPE_CPU: c_int = 1;
/// `OIDN_FORMAT_FLOAT3`.
pub const FORMAT_FLOAT3: c_int = 3;

/// The functions used, resolved from one loaded library.
pub struct Api {
    new_device: unsafe extern "C" fn(c_int) -> Device,
    set_device_int: unsafe extern "C" fn(Device, *const c_char, c_int),
    get_device_int: unsafe extern "C" fn(Device, *const c_char) -> c_int,
    commit_device: unsafe extern "C" fn(Device),
    release_device: unsafe extern "C" fn(Device),
    get_device_error: unsafe extern "C" fn(Device, *mut *const c_char) -> c_int,
    new_filter: unsafe extern "C" fn(Device, *const c_char) -> Filter,
    set_shared_filter_image: unsafe extern "C" fn(
        Filter,
        *const c_char,
        *mut c_void,
        c_int,
        usize,
        usize,
        usize,
        usize,
        usize,
    ),
    set_filter_bool: unsafe extern "C" fn(Filter, *const c_char, bool),
    set_filter_int: unsafe extern "C" fn(Filter, *const c_char, c_int),
    commit_filter: unsafe extern "C" fn(Filter),
    execute_filter: unsafe extern "C" fn(Filter),
    release_filter: unsafe extern "C" fn(Filter),
    /// Owns the code the pointers above point into: dropped last.
    _library: libloading::Library,
}

impl Api {
    /// Loads the library at `name` (a path, or a bare name for the system's loader) and resolves
    /// every entry point; the reason when the file is missing or is not OIDN 2.x.
    pub fn load(name: &std::ffi::OsStr) -> Result<Api, String> {
        // SAFETY: loading runs the library's initialisers; OIDN's only set up its own state.
        let library = unsafe { libloading::Library::new(name) }.map_err(|e| e.to_string())?;
        // SAFETY: each symbol is resolved by its OIDN 2.x name and given the signature of
        // OIDN 2's C header (oidn.h); the pointers live no longer than `library` (same struct).
        unsafe {
            macro_rules! sym {
                ($name:literal) => {
                    *library
                        .get(concat!($name, "\0").as_bytes())
                        .map_err(|e| format!("not Open Image Denoise 2.x ({}: {e})", $name))?
                };
            }
            Ok(Api {
                new_device: sym!("oidnNewDevice"),
                set_device_int: sym!("oidnSetDeviceInt"),
                get_device_int: sym!("oidnGetDeviceInt"),
                commit_device: sym!("oidnCommitDevice"),
                release_device: sym!("oidnReleaseDevice"),
                get_device_error: sym!("oidnGetDeviceError"),
                new_filter: sym!("oidnNewFilter"),
                set_shared_filter_image: sym!("oidnSetSharedFilterImage"),
                set_filter_bool: sym!("oidnSetFilterBool"),
                set_filter_int: sym!("oidnSetFilterInt"),
                commit_filter: sym!("oidnCommitFilter"),
                execute_filter: sym!("oidnExecuteFilter"),
                release_filter: sym!("oidnReleaseFilter"),
                _library: library,
            })
        }
    }
}

fn c(name: &str) -> CString {
    // The names passed are literals of this module, without NUL bytes.
    CString::new(name).unwrap_or_default()
}

/// A committed CPU device. Used by one thread at a time (the owner holds it behind a lock).
pub struct CpuDevice {
    api: Api,
    device: Device,
}

// SAFETY: OIDN devices may be used from any thread, one call at a time; `Denoiser` serialises
// every call through a mutex.
unsafe impl Send for CpuDevice {}

impl CpuDevice {
    /// A CPU device with `threads` worker threads (0: OIDN's choice); its version (e.g. 20501).
    pub fn new(api: Api, threads: usize) -> Result<(CpuDevice, i32), String> {
        // SAFETY: the API's contract: a device handle from oidnNewDevice, names NUL-terminated.
        unsafe {
            let device = (api.new_device)(DEVICE_TYPE_CPU);
            if device.is_null() {
                return Err("Open Image Denoise could not create a CPU device".to_owned());
            }
            let dev = CpuDevice { api, device };
            if threads > 0 {
                let n = c_int::try_from(threads).unwrap_or(c_int::MAX);
                (dev.api.set_device_int)(device, c("numThreads").as_ptr(), n);
            }
            (dev.api.commit_device)(device);
            dev.check("creating the CPU device")?;
            let version = (dev.api.get_device_int)(device, c("version").as_ptr());
            Ok((dev, version))
        }
    }

    /// The device's pending error, if any, with what was being done.
    pub fn check(&self, doing: &str) -> Result<(), String> {
        let mut message: *const c_char = std::ptr::null();
        // SAFETY: a live device; OIDN returns a NUL-terminated message or null.
        let code = unsafe { (self.api.get_device_error)(self.device, &mut message) };
        if code == 0 {
            return Ok(());
        }
        let text = if message.is_null() {
            String::new()
        } else {
            // SAFETY: non-null, NUL-terminated, valid until the next call on this device.
            unsafe { CStr::from_ptr(message) }
                .to_string_lossy()
                .into_owned()
        };
        Err(format!(
            "Open Image Denoise failed {doing} (error {code}): {text}"
        ))
    }

    /// A new filter of type `kind` ("RT").
    pub fn filter(&self, kind: &str) -> Result<FilterHandle<'_>, String> {
        // SAFETY: a live device and a NUL-terminated name.
        let f = unsafe { (self.api.new_filter)(self.device, c(kind).as_ptr()) };
        self.check("creating a filter")?;
        if f.is_null() {
            return Err(format!("Open Image Denoise has no {kind} filter"));
        }
        Ok(FilterHandle {
            device: self,
            filter: f,
        })
    }
}

impl Drop for CpuDevice {
    fn drop(&mut self) {
        // SAFETY: the handle came from oidnNewDevice and is released once.
        unsafe { (self.api.release_device)(self.device) }
    }
}

/// A filter of one device, released on drop.
pub struct FilterHandle<'d> {
    device: &'d CpuDevice,
    filter: Filter,
}

impl FilterHandle<'_> {
    /// Points image `name` at `pixels` (RGB float triples, row-major, `width` x `height`).
    ///
    /// # Safety
    /// `pixels` must stay alive and unmoved, and hold `width * height * 3` floats, until the
    /// filter is executed for the last time or dropped.
    pub unsafe fn set_image(&self, name: &str, pixels: *mut f32, width: usize, height: usize) {
        let api = &self.device.api;
        // SAFETY: the caller's contract; strides 0 mean tightly packed.
        unsafe {
            (api.set_shared_filter_image)(
                self.filter,
                c(name).as_ptr(),
                pixels.cast(),
                FORMAT_FLOAT3,
                width,
                height,
                0,
                0,
                0,
            );
        }
    }

    pub fn set_bool(&self, name: &str, value: bool) {
        // SAFETY: a live filter and a NUL-terminated name.
        unsafe { (self.device.api.set_filter_bool)(self.filter, c(name).as_ptr(), value) }
    }

    pub fn set_int(&self, name: &str, value: i32) {
        // SAFETY: a live filter and a NUL-terminated name.
        unsafe { (self.device.api.set_filter_int)(self.filter, c(name).as_ptr(), value) }
    }

    pub fn commit(&self) -> Result<(), String> {
        // SAFETY: a live filter.
        unsafe { (self.device.api.commit_filter)(self.filter) };
        self.device.check("preparing the filter")
    }

    pub fn execute(&self) -> Result<(), String> {
        // SAFETY: a live, committed filter whose images the caller keeps alive.
        unsafe { (self.device.api.execute_filter)(self.filter) };
        self.device.check("denoising")
    }
}

impl Drop for FilterHandle<'_> {
    fn drop(&mut self) {
        // SAFETY: the handle came from oidnNewFilter and is released once.
        unsafe { (self.device.api.release_filter)(self.filter) }
    }
}
