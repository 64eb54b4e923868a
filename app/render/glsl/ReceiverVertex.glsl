// Vertex stage of an eclipse receiver (EclipseShading). Inserted in place of the camera
// declarations tag of VTK's poly-data vertex shader, so it declares the two camera
// matrices itself: MCVCMatrix is then always present (VTK only declares it for lit
// actors) and VTK sets both. (No VTK tag may appear in these files, comments included:
// VTK substitutes them anywhere.)
//
// A receiver's model coordinates are centred on the body with the world's axes (the
// actor only translates by centre - origin), so vertexMC is the position relative to
// the body's centre: small numbers, full float precision at any distance.
uniform mat4 MCDCMatrix;
uniform mat4 MCVCMatrix;

out vec3 umbraPosMC;              // rasterised facet point, body-centred (m)
flat out vec3 umbraEyeMC;         // camera position, body-centred (perspective)
flat out vec3 umbraViewDirMC;     // direction of projection (parallel)
flat out int umbraParallel;       // 1 for a parallel projection

void umbraReceiverVertex(vec4 posMC) {
  umbraPosMC = posMC.xyz;
  mat4 vcmc = inverse(MCVCMatrix);
  umbraEyeMC = (vcmc * vec4(0.0, 0.0, 0.0, 1.0)).xyz;
  umbraViewDirMC = normalize((vcmc * vec4(0.0, 0.0, -1.0, 0.0)).xyz);
  // The projection's w row is (0, 0, -1, 0) for a perspective, (0, 0, 0, 1) for a
  // parallel projection.
  mat4 vcdc = MCDCMatrix * vcmc;
  umbraParallel = abs(vcdc[2][3]) < 0.5 ? 1 : 0;
}
