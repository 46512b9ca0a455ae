//! The S-shape test piece of ISO 10791-7:2020 (Chanal, Duc & Chevalier, Precision Engineering
//! 75, 2022): geometry, flank-milling overcut, the machining defect of a head-B / table-C
//! machine's location errors, and their identification from measured deviations.

pub mod bspline;
pub mod identify;
pub mod machine;
pub mod overcut;
pub mod part;
pub mod results;
pub mod study;
