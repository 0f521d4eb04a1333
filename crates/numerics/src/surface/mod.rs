//! Stage 1: surfaces — height maps, readers, statistics, synthetic generation, summits.

mod amplitude;
mod fill;
mod filter;
mod form;
mod functional;
mod gradient;
mod height_map;
pub mod io;
mod model_psd;
mod order;
mod resample;
mod summits;

pub use amplitude::{amplitude_statistics, AmplitudeError, AmplitudeStatistics};
pub use fill::{fill_missing, FillError, FillOptions, FilledSurface};
pub use filter::{
    gaussian_band_pass, gaussian_high_pass, gaussian_low_pass, FilterError, GAUSSIAN_ALPHA,
    KERNEL_HALF_WIDTH_IN_CUTOFFS,
};
pub use form::{
    remove_plane, remove_polynomial_form, FormError, FormRemoval, LegendreTerm, MAX_FORM_DEGREE,
};
pub use functional::{
    functional_parameters, functional_parameters_of, FunctionalError, FunctionalOptions,
    FunctionalParameters, MaterialRatioCurve, EQUIVALENT_LINE_SPAN,
};
pub use gradient::{
    gradient_statistics, Boundary, DifferenceScheme, GradientError, GradientStatistics,
};
pub use height_map::{HeightMap, HeightMapError};
pub use resample::{crop, decimate, resample_bilinear, ResampleError};
pub use summits::{find_summits, Summit, SummitError, SummitOptions, SummitStatistics, Summits};
pub mod spectral;
pub mod synthetic;
pub mod twins;
