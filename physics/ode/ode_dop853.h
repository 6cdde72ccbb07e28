// The Dormand-Prince 8(5,3) explicit Runge-Kutta method (DOP853 of Hairer, Norsett &
// Wanner, Solving ODEs I, II.5 and II.10; the coefficients are the published ones of
// their DOP853 code) with its 7th-order continuous extension (II.6). Internal to
// physics/.
//
// Why an eighth-order method for the impulse ODEs: where their solution is smooth a
// step of length h errs by about (h / L)^(p+1), so at the tolerances of a reference
// (1e-12) the 8th-order pair takes far fewer steps than a 5th-order one for twice the
// evaluations a step. Where a friction direction swings round near a small slip the
// step is held down by the distance to that singularity whatever the order, and the
// pair saves too few steps: docs/impact-methods.md measures where it pays.
//
// Twelve stages (the first is the previous step's last: FSAL), an embedded 5th-order
// and 3rd-order error estimate combined as in DOP853 (ErrorNorm853), and a dense
// output that costs three more evaluations and is built only when an event needs it.
// Header-only templates over a fixed-size Eigen vector: no allocation, no exception,
// no virtual call.
#pragma once

#include <array>
#include <cmath>
#include <cstddef>

namespace snooker::physics::ode {

namespace dop853 {
// Nodes of the stages the error estimate and the dense output need explicitly.
inline constexpr double kC14 = 0.1, kC15 = 0.2, kC16 = 7.0 / 9.0;

inline constexpr double kA21 = 5.26001519587677318785587544488e-2;
inline constexpr double kA31 = 1.97250569845378994544595329183e-2;
inline constexpr double kA32 = 5.91751709536136983633785987549e-2;
inline constexpr double kA41 = 2.95875854768068491816892993775e-2;
inline constexpr double kA43 = 8.87627564304205475450678981324e-2;
inline constexpr double kA51 = 2.41365134159266685502369798665e-1;
inline constexpr double kA53 = -8.84549479328286085344864962717e-1;
inline constexpr double kA54 = 9.24834003261792003115737966543e-1;
inline constexpr double kA61 = 3.7037037037037037037037037037e-2;
inline constexpr double kA64 = 1.70828608729473871279604482173e-1;
inline constexpr double kA65 = 1.25467687566822425016691814123e-1;
inline constexpr double kA71 = 3.7109375e-2;
inline constexpr double kA74 = 1.70252211019544039314978060272e-1;
inline constexpr double kA75 = 6.02165389804559606850219397283e-2;
inline constexpr double kA76 = -1.7578125e-2;
inline constexpr double kA81 = 3.70920001185047927108779319836e-2;
inline constexpr double kA84 = 1.70383925712239993810214054705e-1;
inline constexpr double kA85 = 1.07262030446373284651809199168e-1;
inline constexpr double kA86 = -1.53194377486244017527936158236e-2;
inline constexpr double kA87 = 8.27378916381402288758473766002e-3;
inline constexpr double kA91 = 6.24110958716075717114429577812e-1;
inline constexpr double kA94 = -3.36089262944694129406857109825e0;
inline constexpr double kA95 = -8.68219346841726006818189891453e-1;
inline constexpr double kA96 = 2.75920996994467083049415600797e1;
inline constexpr double kA97 = 2.01540675504778934086186788979e1;
inline constexpr double kA98 = -4.34898841810699588477366255144e1;
inline constexpr double kA101 = 4.77662536438264365890433908527e-1;
inline constexpr double kA104 = -2.48811461997166764192642586468e0;
inline constexpr double kA105 = -5.90290826836842996371446475743e-1;
inline constexpr double kA106 = 2.12300514481811942347288949897e1;
inline constexpr double kA107 = 1.52792336328824235832596922938e1;
inline constexpr double kA108 = -3.32882109689848629194453265587e1;
inline constexpr double kA109 = -2.03312017085086261358222928593e-2;
inline constexpr double kA111 = -9.3714243008598732571704021658e-1;
inline constexpr double kA114 = 5.18637242884406370830023853209e0;
inline constexpr double kA115 = 1.09143734899672957818500254654e0;
inline constexpr double kA116 = -8.14978701074692612513997267357e0;
inline constexpr double kA117 = -1.85200656599969598641566180701e1;
inline constexpr double kA118 = 2.27394870993505042818970056734e1;
inline constexpr double kA119 = 2.49360555267965238987089396762e0;
inline constexpr double kA1110 = -3.0467644718982195003823669022e0;
inline constexpr double kA121 = 2.27331014751653820792359768449e0;
inline constexpr double kA124 = -1.05344954667372501984066689879e1;
inline constexpr double kA125 = -2.00087205822486249909675718444e0;
inline constexpr double kA126 = -1.79589318631187989172765950534e1;
inline constexpr double kA127 = 2.79488845294199600508499808837e1;
inline constexpr double kA128 = -2.85899827713502369474065508674e0;
inline constexpr double kA129 = -8.87285693353062954433549289258e0;
inline constexpr double kA1210 = 1.23605671757943030647266201528e1;
inline constexpr double kA1211 = 6.43392746015763530355970484046e-1;
// 8th-order weights (b2..b5 are zero).
inline constexpr double kB1 = 5.42937341165687622380535766363e-2;
inline constexpr double kB6 = 4.45031289275240888144113950566e0;
inline constexpr double kB7 = 1.89151789931450038304281599044e0;
inline constexpr double kB8 = -5.8012039600105847814672114227e0;
inline constexpr double kB9 = 3.1116436695781989440891606237e-1;
inline constexpr double kB10 = -1.52160949662516078556178806805e-1;
inline constexpr double kB11 = 2.01365400804030348374776537501e-1;
inline constexpr double kB12 = 4.47106157277725905176885569043e-2;
// The 3rd-order comparison: the 8th-order increment less these weights.
inline constexpr double kBhh1 = 0.244094488188976377952755905512;
inline constexpr double kBhh2 = 0.733846688281611857341361741547;
inline constexpr double kBhh3 = 0.220588235294117647058823529412e-1;
// The 5th-order error estimate's weights.
inline constexpr double kEr1 = 0.1312004499419488073250102996e-1;
inline constexpr double kEr6 = -0.1225156446376204440720569753e1;
inline constexpr double kEr7 = -0.4957589496572501915214079952;
inline constexpr double kEr8 = 0.1664377182454986536961530415e1;
inline constexpr double kEr9 = -0.3503288487499736816886487290;
inline constexpr double kEr10 = 0.3341791187130174790297318841;
inline constexpr double kEr11 = 0.8192320648511571246570742613e-1;
inline constexpr double kEr12 = -0.2235530786388629525884427845e-1;
// Stages 14-16 of the dense output (stage 13 is the derivative at y1).
inline constexpr double kA141 = 5.61675022830479523392909219681e-2;
inline constexpr double kA147 = 2.53500210216624811088794765333e-1;
inline constexpr double kA148 = -2.46239037470802489917441475441e-1;
inline constexpr double kA149 = -1.24191423263816360469010140626e-1;
inline constexpr double kA1410 = 1.5329179827876569731206322685e-1;
inline constexpr double kA1411 = 8.20105229563468988491666602057e-3;
inline constexpr double kA1412 = 7.56789766054569976138603589584e-3;
inline constexpr double kA1413 = -8.298e-3;
inline constexpr double kA151 = 3.18346481635021405060768473261e-2;
inline constexpr double kA156 = 2.83009096723667755288322961402e-2;
inline constexpr double kA157 = 5.35419883074385676223797384372e-2;
inline constexpr double kA158 = -5.49237485713909884646569340306e-2;
inline constexpr double kA1511 = -1.08347328697249322858509316994e-4;
inline constexpr double kA1512 = 3.82571090835658412954920192323e-4;
inline constexpr double kA1513 = -3.40465008687404560802977114492e-4;
inline constexpr double kA1514 = 1.41312443674632500278074618366e-1;
inline constexpr double kA161 = -4.28896301583791923408573538692e-1;
inline constexpr double kA166 = -4.69762141536116384314449447206e0;
inline constexpr double kA167 = 7.68342119606259904184240953878e0;
inline constexpr double kA168 = 4.06898981839711007970213554331e0;
inline constexpr double kA169 = 3.56727187455281109270669543021e-1;
inline constexpr double kA1613 = -1.39902416515901462129418009734e-3;
inline constexpr double kA1614 = 2.9475147891527723389556272149e0;
inline constexpr double kA1615 = -9.15095847217987001081870187138e0;
// Dense output: rows 4-7 of the continuous extension's coefficients, over stages
// 1, 6-16 (stages 2-5 do not appear).
inline constexpr std::array<double, 12> kD4 = {
    -0.84289382761090128651353491142e1, 0.56671495351937776962531783590,
    -0.30689499459498916912797304727e1, 0.23846676565120698287728149680e1,
    0.21170345824450282767155149946e1,  -0.87139158377797299206789907490,
    0.22404374302607882758541771650e1,  0.63157877876946881815570249290,
    -0.88990336451333310820698117400e-1, 0.18148505520854727256656404962e2,
    -0.91946323924783554000451984436e1, -0.44360363875948939664310572000e1};
inline constexpr std::array<double, 12> kD5 = {
    0.10427508642579134603413151009e2,  0.24228349177525818288430175319e3,
    0.16520045171727028198505394887e3,  -0.37454675472269020279518312152e3,
    -0.22113666853125306036270938578e2, 0.77334326684722638389603898808e1,
    -0.30674084731089398182061213626e2, -0.93321305264302278729567221706e1,
    0.15697238121770843886131091075e2,  -0.31139403219565177677282850411e2,
    -0.93529243588444783865713862664e1, 0.35816841486394083752465898540e2};
inline constexpr std::array<double, 12> kD6 = {
    0.19985053242002433820987653617e2,  -0.38703730874935176555105901742e3,
    -0.18917813819516756882830838328e3, 0.52780815920542364900561016686e3,
    -0.11573902539959630126141871134e2, 0.68812326946963000169666922661e1,
    -0.10006050966910838403183860980e1, 0.77771377980534432092869265740,
    -0.27782057523535084065932004339e1, -0.60196695231264120758267380846e2,
    0.84320405506677161018159903784e2,  0.11992291136182789328035130030e2};
inline constexpr std::array<double, 12> kD7 = {
    -0.25693933462703749003312586129e2, -0.15418974869023643374053993627e3,
    -0.23152937917604549567536039109e3, 0.35763911791061412378285349910e3,
    0.93405324183624310003907691704e2,  -0.37458323136451633156875139351e2,
    0.10409964950896230045147246184e3,  0.29840293426660503123344363579e2,
    -0.43533456590011143754432175058e2, 0.96324553959188282948394950600e2,
    -0.39177261675615439165231486172e2, -0.14972683625798562581422125276e3};
}  // namespace dop853

/// Result of one DOP853 step.
template <class Y>
struct Dop853Result {
  Y y1;               ///< 8th-order solution at the end of the step
  Y k13;              ///< derivative at y1 (the next step's first stage, FSAL)
  Y err5;             ///< 5th-order error estimate (times h)
  Y err3;             ///< 3rd-order comparison (times h), for ErrorNorm853
  bool valid = true;  ///< false if a derivative was undefined or y1 is not finite
  /// Stages 1 and 6-12, kept for the dense output (stages 2-5 do not enter it).
  std::array<Y, 8> k;
  double h = 0;
};

/// DOP853's error norm from the two estimates, each already reduced to a number (for
/// example the weighted max-norm over its components, relative to the tolerance):
/// e5^2 / sqrt(e5^2 + 0.01 e3^2). The 3rd-order comparison keeps the estimate from
/// vanishing by accident where the 5th-order one does.
inline double ErrorNorm853(double e5, double e3) {
  const double deno = e5 * e5 + 0.01 * e3 * e3;
  return deno > 0 ? e5 * e5 / std::sqrt(deno) : 0.0;
}

/// One step of length `h` from `y0`, whose derivative is `k1`; `rhs` and `observe` as
/// for Dp54Step.
template <class Y, class Rhs, class Observe>
void Dop853Step(const Y& y0, const Y& k1, double h, Rhs&& rhs, Observe&& observe,
                Dop853Result<Y>* out) {
  using namespace dop853;
  Y k2, k3, k4, k5, k6, k7, k8, k9, k10, k11, k12, y;
  bool ok = true;
  y = y0 + h * kA21 * k1;
  observe(y);
  ok &= rhs(y, &k2);
  y = y0 + h * (kA31 * k1 + kA32 * k2);
  observe(y);
  ok &= rhs(y, &k3);
  y = y0 + h * (kA41 * k1 + kA43 * k3);
  observe(y);
  ok &= rhs(y, &k4);
  y = y0 + h * (kA51 * k1 + kA53 * k3 + kA54 * k4);
  observe(y);
  ok &= rhs(y, &k5);
  y = y0 + h * (kA61 * k1 + kA64 * k4 + kA65 * k5);
  observe(y);
  ok &= rhs(y, &k6);
  y = y0 + h * (kA71 * k1 + kA74 * k4 + kA75 * k5 + kA76 * k6);
  observe(y);
  ok &= rhs(y, &k7);
  y = y0 + h * (kA81 * k1 + kA84 * k4 + kA85 * k5 + kA86 * k6 + kA87 * k7);
  observe(y);
  ok &= rhs(y, &k8);
  y = y0 + h * (kA91 * k1 + kA94 * k4 + kA95 * k5 + kA96 * k6 + kA97 * k7 + kA98 * k8);
  observe(y);
  ok &= rhs(y, &k9);
  y = y0 + h * (kA101 * k1 + kA104 * k4 + kA105 * k5 + kA106 * k6 + kA107 * k7 + kA108 * k8 +
                kA109 * k9);
  observe(y);
  ok &= rhs(y, &k10);
  y = y0 + h * (kA111 * k1 + kA114 * k4 + kA115 * k5 + kA116 * k6 + kA117 * k7 + kA118 * k8 +
                kA119 * k9 + kA1110 * k10);
  observe(y);
  ok &= rhs(y, &k11);
  y = y0 + h * (kA121 * k1 + kA124 * k4 + kA125 * k5 + kA126 * k6 + kA127 * k7 + kA128 * k8 +
                kA129 * k9 + kA1210 * k10 + kA1211 * k11);
  observe(y);
  ok &= rhs(y, &k12);
  const Y incr = kB1 * k1 + kB6 * k6 + kB7 * k7 + kB8 * k8 + kB9 * k9 + kB10 * k10 +
                 kB11 * k11 + kB12 * k12;
  out->y1 = y0 + h * incr;
  observe(out->y1);
  ok &= rhs(out->y1, &out->k13);
  out->err3 = h * (incr - kBhh1 * k1 - kBhh2 * k9 - kBhh3 * k12);
  out->err5 = h * (kEr1 * k1 + kEr6 * k6 + kEr7 * k7 + kEr8 * k8 + kEr9 * k9 + kEr10 * k10 +
                   kEr11 * k11 + kEr12 * k12);
  out->k = {k1, k6, k7, k8, k9, k10, k11, k12};
  out->h = h;
  out->valid = ok && out->y1.allFinite();
}

/// DOP853's continuous extension of a step (order 7). Building it evaluates the
/// right-hand side three times (stages 14-16); `rhs` as for the step, in the same
/// mode. valid() is false if one of them was undefined.
template <class Y>
class Dop853Dense {
 public:
  Dop853Dense() = default;
  template <class Rhs>
  Dop853Dense(const Y& y0, const Dop853Result<Y>& s, Rhs&& rhs) {
    using namespace dop853;
    const std::array<Y, 8>& k = s.k;  // k1, k6..k12
    const Y& k13 = s.k13;
    const double h = s.h;
    Y k14, k15, k16;
    bool ok = true;
    ok &= rhs(Y(y0 + h * (kA141 * k[0] + kA147 * k[2] + kA148 * k[3] + kA149 * k[4] +
                          kA1410 * k[5] + kA1411 * k[6] + kA1412 * k[7] + kA1413 * k13)),
              &k14);
    ok &= rhs(Y(y0 + h * (kA151 * k[0] + kA156 * k[1] + kA157 * k[2] + kA158 * k[3] +
                          kA1511 * k[6] + kA1512 * k[7] + kA1513 * k13 + kA1514 * k14)),
              &k15);
    ok &= rhs(Y(y0 + h * (kA161 * k[0] + kA166 * k[1] + kA167 * k[2] + kA168 * k[3] +
                          kA169 * k[4] + kA1613 * k13 + kA1614 * k14 + kA1615 * k15)),
              &k16);
    valid_ = ok;
    const std::array<const Y*, 12> stage = {&k[0], &k[1], &k[2], &k[3], &k[4], &k[5],
                                            &k[6], &k[7], &k13,  &k14,  &k15,  &k16};
    auto row = [&](const std::array<double, 12>& d) {
      Y r = d[0] * *stage[0];
      for (std::size_t i = 1; i < 12; ++i) r += d[i] * *stage[i];
      return Y(h * r);
    };
    r_[0] = s.y1 - y0;
    r_[1] = h * k[0] - r_[0];
    r_[2] = r_[0] - h * k13 - r_[1];
    r_[3] = row(kD4);
    r_[4] = row(kD5);
    r_[5] = row(kD6);
    r_[6] = row(kD7);
  }
  bool valid() const { return valid_; }
  /// The state at the fraction t in [0, 1] of the step.
  Y At(const Y& y0, double t) const {
    const double u = 1 - t;
    const Y inner = r_[3] + t * (r_[4] + u * (r_[5] + t * r_[6]));
    return y0 + t * (r_[0] + u * (r_[1] + t * (r_[2] + u * inner)));
  }

 private:
  std::array<Y, 7> r_;
  bool valid_ = true;
};

}  // namespace snooker::physics::ode
