// Anchor source of the Verilated sm_top libraries (the model sources are added by verilate()).
