//! Stage 3: the textbook quantities, as pure functions over plain data.
