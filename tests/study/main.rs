//! The study format: angles and their units, broken studies, the messages of a corpus of failures, parameter references inside strings and glob axes, overrides, parser robustness, summaries, input traps of measured files.

mod angle_units;
mod input_traps;
mod message_corpus;
mod special_files;
mod study_errors;
mod study_interpolation;
mod study_overrides;
mod study_parser_robustness;
mod study_summaries;
