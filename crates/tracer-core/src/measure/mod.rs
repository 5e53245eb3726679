//! Sensors and calculation grids: the illuminance at points with a normal, with its standard
//! error. Sensors block no light; each point's estimate comes from the integrator's irradiance
//! estimator, sampled with streams keyed by (grid, point, sample index).

mod buried;
mod daylight_factor;
mod grid;
pub mod isolux;
pub mod partial;
pub mod placement;
pub mod requirements;
pub mod rounding;
mod sensor_sum;
mod sensors;

pub use buried::{buried_points, front_winding, is_buried, mark_buried};
pub use daylight_factor::{DF_OUTDOOR_LX, DaylightFactorSetup};
pub use grid::{Grid, GridError, SensorPoint};
pub use sensor_sum::SensorSum;
pub use sensors::{
    GridResult, GridStatistics, MeasureProgress, MeasureSettings, PointResult, TARGET_MIN_SAMPLES,
    grid_results, measure_grids, measure_grids_with_progress, measure_samples,
};
