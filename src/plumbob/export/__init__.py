"""Mass properties written in other programs' formats (simulator inertial blocks)."""
