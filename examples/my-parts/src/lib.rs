//! My parts: the `.lmd` files in `parts/` and their tests in `tests/`.
