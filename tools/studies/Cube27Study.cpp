// Cube27Study: being written (see tools/studies/Cube27Study.h when it lands).
