//VTK::Normal::Impl
  normalVCVSOutput = normalMatrix * tcNormalMC;
