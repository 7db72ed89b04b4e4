//! ldh-py
