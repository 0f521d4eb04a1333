//! Stage 3: statistical and per-summit static-friction models (Greenwood–Williamson, Kogut–Etsion, CEB).
