//! The integration tests, one module per capability, in one binary (one
//! link of the library and GMP instead of one per file).

mod common;

mod area;
mod atlas;
mod budget;
mod claims;
mod claims_cli;
mod cli;
mod edge_inputs;
mod elementary;
mod exact_text;
mod files;
mod findings;
mod fuzz_cli;
mod inclusion;
mod loose_checker;
mod mechanics;
mod methods;
mod motion;
mod param_proofs;
mod params;
mod paving;
mod peers;
mod proof_mutations;
mod proofs;
mod reference;
mod roots;
mod roots_request;
mod scene_files;
mod scene_format;
mod singular;
mod soundness;
mod stability;
mod statements;
mod verify_files;
