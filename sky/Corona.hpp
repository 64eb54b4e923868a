#pragma once
// The solar corona seen in totality: its radiance against the distance from the Sun's
// centre, from Baumbach's radial model (Baumbach 1937, Astron. Nachr. 263, 121; as tabled in
// Allen's Astrophysical Quantities) of the K (electron) and F (dust) corona together,
// averaged over position angle, in units of the mean radiance of the solar disc:
//     B(rho) / B_disc = 1e-6 (0.0532 rho^-2.5 + 1.425 rho^-7 + 2.565 rho^-17),
// rho in solar radii from the Sun's centre (rho >= 1). The first term is the F corona, the
// other two the K corona (the Baumbach-Allen electron density, 1e8 (2.99 rho^-16 +
// 1.55 rho^-6) cm^-3, scattering the Sun's light diluted as rho^-2, seen along the line of
// sight). Streamers and the corona's flattening at solar minimum are not modelled.
namespace umbra::sky {

/// B(rho) / B_disc of the K + F corona; 0 inside the disc (rho < 1).
double coronaRelativeRadiance(double rhoSolarRadii);
/// The F (dust) part alone: 1e-6 * 0.0532 rho^-2.5.
double fCoronaRelativeRadiance(double rhoSolarRadii);

/// The corona's flux outside rho0 (>= 1) as a fraction of the whole solar disc's (the
/// closed-form integral of B over rings, 2 int_{rho0}^inf B(rho) / B_disc rho drho, the
/// disc's flux being pi B_disc in the same units): 1.12e-6 from the limb out.
double coronaFluxFractionOutside(double rho0SolarRadii);

}  // namespace umbra::sky
