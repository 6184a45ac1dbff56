// DXF drawings: not written yet.
