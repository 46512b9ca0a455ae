//! The engine's integration tests: one test binary (linked once, not once per file), its
//! modules mirroring `crate/src/` (`ballbar/…` tests `crate/src/ballbar/`, `lib/` the crate as a
//! whole). Each test is named for the behaviour it checks; `cargo test -p fiveaxis --test engine
//! -- cubic::paper` runs one file's tests. A new file needs its `mod` line here
//! (`lib::test_tree` fails without it).

mod common;
mod probe_common;

mod api {
    mod call;
}
mod ballbar {
    mod iso230_4;
    mod rotary_identified_errors_are_the_machines;
    mod rotary_identify_monte_carlo;
    mod rotary_reader;
    mod rotary_sensitivities;
    mod rotary_trace;
    mod to_machine;
}
mod chain {
    mod model;
}
mod csv {
    mod decimal;
    mod decimal_comma;
}
mod cubic {
    mod analysis;
    mod any_machine;
    mod design;
    mod design_search;
    mod identify;
    mod paper;
}
mod identify {
    mod decisions;
    mod monte_carlo;
    mod stats;
}
mod lib {
    mod module_graph;
    mod test_tree;
}
mod machine {
    mod model;
    mod motions;
    mod schematic;
    mod travel;
}
mod nonlinear {
    mod deviation;
    mod fast_peak;
    mod inputs;
    mod outputs;
    mod paper;
    mod split;
}
mod positioning {
    mod iso230_2;
}
mod probe {
    mod centres_and_sensitivities;
    mod csv_reader;
    mod design_and_visibility;
    mod design_scaling_and_limits;
    mod fit_check_and_group_units;
    mod identified_errors_are_the_machines;
    mod identify_monte_carlo;
}
mod reversal {
    mod fit;
    mod friction;
    mod measure;
    mod motion;
    mod study;
}
mod rotary {
    mod kinematics;
}
mod schema {
    mod describe;
    mod read;
}
mod sshape {
    mod any_machine;
    mod definitions;
    mod eq14_vs_chain;
    mod geometry;
    mod identify;
    mod machine;
    mod overcut;
}
mod toolpath {
    mod analysis;
    mod compare;
    mod export;
    mod parse;
    mod parse_limits;
    mod program;
    mod read_apt;
    mod read_bytes;
    mod read_frame;
    mod read_heidenhain;
    mod read_iso;
    mod read_nc;
    mod read_siemens;
    mod real_files;
}
mod volumetric {
    mod map;
    mod paper;
}
