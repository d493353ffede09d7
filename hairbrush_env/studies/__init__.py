"""Studies reproducing thesis results (chapter 2): double-helix combing, hair-curl census, parallel sweeps."""
