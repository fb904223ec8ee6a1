/* cablesys dopri5: Dormand-Prince 5(4) with error control and dense output, a block of output
 * times per call, in CasADi's external-function C API (see cablesys/time_domain/dopri5.py).
 *
 * Appended by cablesys.time_domain.dopri5 to the C that CasADi's CodeGenerator generates for the
 * model's relative-time ODE, after these definitions (prepended by the Python side):
 *   CS_DP5_NX        number of states
 *   CS_DP5_NP        length of the integrator's p (the model's p, then t0 and h)
 *   CS_DP5_NK        output times per call (a block; the x output is NX x NK)
 *   CS_DP5_RHS       the generated right-hand side, (s, x, z, p, u) -> (x', alg, quad, zero)
 *   CS_DP5_RHS_WORK  its work-size function
 *
 * Method: Dormand & Prince (1980), "A family of embedded Runge-Kutta formulae", J. Comput. Appl.
 * Math. 6(1), 19-26 (coefficients a_ij, c_i, b_i; first same as last); error estimate, PI step
 * control, initial step and dense output as in Hairer, Norsett & Wanner, Solving Ordinary
 * Differential Equations I (2nd ed. 1993), sec. II.4 (error norm eq. 4.11, step factor eq. 4.13,
 * initial step "starting step size" algorithm), II.5 (Table 5.2), II.6 (dense output of DOPRI5,
 * the coefficients d_i of Hairer's DOPRI5 code, CONTD5), and Hairer & Wanner, Solving ODEs II,
 * sec. IV.2 (the PI controller, beta = 0.04 as in DOPRI5).
 *
 * The carry (input 0 -> output 0) holds the integrator between output times and calls:
 *   [0] s        current (relative) time       [6]  s_fail   time of a failure
 *   [1] h        proposed next step (0: pick)  [7]  s_old    start of the last accepted step
 *   [2] accepted steps                          [8]  err_old  previous error norm (PI control)
 *   [3] rejected steps                          [9]  k1 valid (first same as last)
 *   [4] right-hand-side evaluations             [10] h_last   length of the last accepted step
 *   [5] status (0 ok, 1 too much work, 2 step too small,   [11] last step rejected
 *       3 step too small, the last rejection non-finite)   [12] the last rejection was for non-finite stages
 *   then x (NX), k1 = f(s, x) (NX), the 5 NX dense-output coefficients of the last accepted step.
 */
#define CS_DP5_HEAD 13
#define CS_DP5_NC (CS_DP5_HEAD + 7 * CS_DP5_NX)
#define CS_DP5_NW (CS_DP5_NC + 8 * CS_DP5_NX)

static const casadi_int cs_dp5_sp_carry[3] = {CS_DP5_NC, 1, 1};
static const casadi_int cs_dp5_sp_times[3] = {CS_DP5_NK, 1, 1};
static const casadi_int cs_dp5_sp_p[3] = {CS_DP5_NP, 1, 1};
static const casadi_int cs_dp5_sp_tol[3] = {2, 1, 1};
static const casadi_int cs_dp5_sp_x[3] = {CS_DP5_NX, 1, 1};
static const casadi_int cs_dp5_sp_xs[3] = {CS_DP5_NX, CS_DP5_NK, 1};

/* Dormand & Prince (1980), Table 2 (DOPRI5; Hairer et al. Table II.5.2) */
static const casadi_real cs_dp5_c2 = 1.0 / 5, cs_dp5_c3 = 3.0 / 10, cs_dp5_c4 = 4.0 / 5, cs_dp5_c5 = 8.0 / 9;
static const casadi_real cs_dp5_a21 = 1.0 / 5;
static const casadi_real cs_dp5_a31 = 3.0 / 40, cs_dp5_a32 = 9.0 / 40;
static const casadi_real cs_dp5_a41 = 44.0 / 45, cs_dp5_a42 = -56.0 / 15, cs_dp5_a43 = 32.0 / 9;
static const casadi_real cs_dp5_a51 = 19372.0 / 6561, cs_dp5_a52 = -25360.0 / 2187, cs_dp5_a53 = 64448.0 / 6561,
                         cs_dp5_a54 = -212.0 / 729;
static const casadi_real cs_dp5_a61 = 9017.0 / 3168, cs_dp5_a62 = -355.0 / 33, cs_dp5_a63 = 46732.0 / 5247,
                         cs_dp5_a64 = 49.0 / 176, cs_dp5_a65 = -5103.0 / 18656;
static const casadi_real cs_dp5_a71 = 35.0 / 384, cs_dp5_a73 = 500.0 / 1113, cs_dp5_a74 = 125.0 / 192,
                         cs_dp5_a75 = -2187.0 / 6784, cs_dp5_a76 = 11.0 / 84;
/* b_i - b^_i: the 5th-order minus the embedded 4th-order weights */
static const casadi_real cs_dp5_e1 = 71.0 / 57600, cs_dp5_e3 = -71.0 / 16695, cs_dp5_e4 = 71.0 / 1920,
                         cs_dp5_e5 = -17253.0 / 339200, cs_dp5_e6 = 22.0 / 525, cs_dp5_e7 = -1.0 / 40;
/* dense output (Hairer et al. II.6; DOPRI5's CONTD5 coefficients, from Shampine 1986) */
static const casadi_real cs_dp5_d1 = -12715105075.0 / 11282082432.0, cs_dp5_d3 = 87487479700.0 / 32700410799.0,
                         cs_dp5_d4 = -10690763975.0 / 1880347072.0, cs_dp5_d5 = 701980252875.0 / 199316789632.0,
                         cs_dp5_d6 = -1453857185.0 / 822651844.0, cs_dp5_d7 = 69997945.0 / 29380423.0;
/* step control (Hairer et al. II.4, IV.2; DOPRI5 defaults): safety, factor bounds, PI beta */
static const casadi_real cs_dp5_safe = 0.9, cs_dp5_fac_min = 0.2, cs_dp5_fac_max = 10.0, cs_dp5_beta = 0.04;
static const casadi_real cs_dp5_uround = 2.3e-16;

static int cs_dp5_isfinite(casadi_real v) { return v - v == 0.0; }

/* out = f(s, x): the generated relative-time ODE (z and u are empty) */
static int cs_dp5_f(casadi_real s, const casadi_real* x, const casadi_real* p, casadi_real* out,
                    const casadi_real** arg, casadi_real** res, casadi_int* iw, casadi_real* w) {
  arg[0] = &s; arg[1] = x; arg[2] = 0; arg[3] = p; arg[4] = 0;
  res[0] = out; res[1] = 0; res[2] = 0; res[3] = 0;
  return CS_DP5_RHS(arg, res, iw, w, 0);
}

/* RMS of v_i / (atol_i + rtol max(|x_i|, |y_i|)) (Hairer et al. eq. II.4.11) */
static casadi_real cs_dp5_norm(const casadi_real* v, const casadi_real* x, const casadi_real* y,
                               casadi_real rtol, const casadi_real* atol) {
  casadi_real sum = 0, sk, ax, ay;
  casadi_int i;
  for (i = 0; i < CS_DP5_NX; ++i) {
    ax = fabs(x[i]);
    ay = y ? fabs(y[i]) : ax;
    sk = (atol ? atol[i] : 0) + rtol * (ax > ay ? ax : ay);
    sum += (v[i] / sk) * (v[i] / sk);
  }
  return sqrt(sum / CS_DP5_NX);
}

/* Advance the carry c (in w) to s_out, at most tol[1] attempted steps, and write x(s_out) to xo. */
static void cs_dp5_advance(casadi_real s_out, const casadi_real* p, const casadi_real* tol, const casadi_real* atol,
                           casadi_real* xo, const casadi_real** sub_arg, casadi_real** sub_res, casadi_int* iw,
                           casadi_real* w) {
  casadi_real* c = w;                       /* the carry */
  casadi_real* k2 = w + CS_DP5_NC;
  casadi_real *k3 = k2 + CS_DP5_NX, *k4 = k3 + CS_DP5_NX, *k5 = k4 + CS_DP5_NX, *k6 = k5 + CS_DP5_NX,
              *k7 = k6 + CS_DP5_NX, *yt = k7 + CS_DP5_NX, *y1 = yt + CS_DP5_NX;
  casadi_real* rw = w + CS_DP5_NW;          /* the right-hand side's work */
  casadi_real *x = c + CS_DP5_HEAD, *k1 = x + CS_DP5_NX, *r = k1 + CS_DP5_NX;
  casadi_real rtol = tol ? tol[0] : 0;
  casadi_int max_steps = tol ? (casadi_int)tol[1] : 0, taken = 0, i;
  casadi_real s, h, err, fac, fac11, hnew, theta, theta1, span, bound, sk, dnf, dny, der2, h1;
  if (max_steps <= 0) max_steps = 100000;
  s = c[0];
  if (!c[9]) {                              /* k1 = f(s, x) unless carried over (FSAL) */
    if (cs_dp5_f(s, x, p, k1, sub_arg, sub_res, iw, rw)) { c[5] = 3; c[6] = s; goto done; }
    c[4] += 1;
    c[9] = 1;
  }
  span = fabs(s_out - s) > 0 ? fabs(s_out - s) : 1.0;
  if (c[1] <= 0 && s < s_out) {            /* starting step (Hairer et al. II.4, "starting step size") */
    dnf = 0; dny = 0;
    for (i = 0; i < CS_DP5_NX; ++i) {
      sk = (atol ? atol[i] : 0) + rtol * fabs(x[i]);
      dnf += (k1[i] / sk) * (k1[i] / sk);
      dny += (x[i] / sk) * (x[i] / sk);
    }
    h = (dnf <= 1e-10 || dny <= 1e-10) ? 1e-6 : 0.01 * sqrt(dny / dnf);
    if (h > span) h = span;
    for (i = 0; i < CS_DP5_NX; ++i) yt[i] = x[i] + h * k1[i];
    if (cs_dp5_f(s + h, yt, p, k2, sub_arg, sub_res, iw, rw)) { c[5] = 3; c[6] = s; goto done; }
    c[4] += 1;
    for (i = 0; i < CS_DP5_NX; ++i) k2[i] -= k1[i];
    der2 = cs_dp5_norm(k2, x, 0, rtol, atol) * sqrt((casadi_real)CS_DP5_NX) / h;
    if (!(der2 > sqrt(dnf))) der2 = sqrt(dnf);
    h1 = der2 <= 1e-15 ? (1e-6 > h * 1e-3 ? 1e-6 : h * 1e-3) : pow(0.01 / der2, 0.2);
    h = 100 * h < h1 ? 100 * h : h1;
    if (!(h > 0) || !cs_dp5_isfinite(h)) h = 1e-6 * span;
    c[1] = h;
  }
  while (s < s_out) {
    h = c[1];
    bound = fabs(s) > fabs(s_out) ? fabs(s) : fabs(s_out);
    if (taken >= max_steps) { c[5] = 1; c[6] = s; goto done; }
    if (0.1 * h <= bound * cs_dp5_uround) { c[5] = c[12] ? 3 : 2; c[6] = s; goto done; }
    ++taken;
    /* stages (Dormand & Prince 1980; Hairer et al. Table II.5.2) */
    for (i = 0; i < CS_DP5_NX; ++i) yt[i] = x[i] + h * cs_dp5_a21 * k1[i];
    if (cs_dp5_f(s + cs_dp5_c2 * h, yt, p, k2, sub_arg, sub_res, iw, rw)) goto rhs_failed;
    for (i = 0; i < CS_DP5_NX; ++i) yt[i] = x[i] + h * (cs_dp5_a31 * k1[i] + cs_dp5_a32 * k2[i]);
    if (cs_dp5_f(s + cs_dp5_c3 * h, yt, p, k3, sub_arg, sub_res, iw, rw)) goto rhs_failed;
    for (i = 0; i < CS_DP5_NX; ++i) yt[i] = x[i] + h * (cs_dp5_a41 * k1[i] + cs_dp5_a42 * k2[i] + cs_dp5_a43 * k3[i]);
    if (cs_dp5_f(s + cs_dp5_c4 * h, yt, p, k4, sub_arg, sub_res, iw, rw)) goto rhs_failed;
    for (i = 0; i < CS_DP5_NX; ++i)
      yt[i] = x[i] + h * (cs_dp5_a51 * k1[i] + cs_dp5_a52 * k2[i] + cs_dp5_a53 * k3[i] + cs_dp5_a54 * k4[i]);
    if (cs_dp5_f(s + cs_dp5_c5 * h, yt, p, k5, sub_arg, sub_res, iw, rw)) goto rhs_failed;
    for (i = 0; i < CS_DP5_NX; ++i)
      yt[i] = x[i] + h * (cs_dp5_a61 * k1[i] + cs_dp5_a62 * k2[i] + cs_dp5_a63 * k3[i] + cs_dp5_a64 * k4[i]
                          + cs_dp5_a65 * k5[i]);
    if (cs_dp5_f(s + h, yt, p, k6, sub_arg, sub_res, iw, rw)) goto rhs_failed;
    for (i = 0; i < CS_DP5_NX; ++i)
      y1[i] = x[i] + h * (cs_dp5_a71 * k1[i] + cs_dp5_a73 * k3[i] + cs_dp5_a74 * k4[i] + cs_dp5_a75 * k5[i]
                          + cs_dp5_a76 * k6[i]);
    if (cs_dp5_f(s + h, y1, p, k7, sub_arg, sub_res, iw, rw)) goto rhs_failed;
    c[4] += 6;
    /* local error estimate h sum (b_i - b^_i) k_i (Hairer et al. eq. II.4.11 norm) */
    for (i = 0; i < CS_DP5_NX; ++i)
      yt[i] = h * (cs_dp5_e1 * k1[i] + cs_dp5_e3 * k3[i] + cs_dp5_e4 * k4[i] + cs_dp5_e5 * k5[i]
                   + cs_dp5_e6 * k6[i] + cs_dp5_e7 * k7[i]);
    err = cs_dp5_norm(yt, x, y1, rtol, atol);
    if (!cs_dp5_isfinite(err)) {             /* a non-finite stage: retry with a much smaller step */
      c[3] += 1; c[11] = 1; c[12] = 1;
      c[1] = h * cs_dp5_fac_min;
      continue;
    }
    /* PI step-size control (Hairer & Wanner, Solving ODEs II, sec. IV.2; DOPRI5): h_new = h / fac,
       fac = err^(1/5 - 0.75 beta) / err_old^beta / safe, bounded to [1/fac_max, 1/fac_min] */
    fac11 = pow(err, 0.2 - cs_dp5_beta * 0.75);
    if (err <= 1.0) {
      fac = fac11 / pow(c[8] > 0 ? c[8] : 1e-4, cs_dp5_beta) / cs_dp5_safe;
      fac = fac < 1.0 / cs_dp5_fac_max ? 1.0 / cs_dp5_fac_max : (fac > 1.0 / cs_dp5_fac_min ? 1.0 / cs_dp5_fac_min : fac);
      hnew = h / fac;
      c[8] = err > 1e-4 ? err : 1e-4;
      c[2] += 1;
      /* dense output of this step (Hairer et al. II.6, DOPRI5's CONTD5) */
      for (i = 0; i < CS_DP5_NX; ++i) {
        r[i] = x[i];
        r[CS_DP5_NX + i] = y1[i] - x[i];
        r[2 * CS_DP5_NX + i] = h * k1[i] - r[CS_DP5_NX + i];
        r[3 * CS_DP5_NX + i] = r[CS_DP5_NX + i] - h * k7[i] - r[2 * CS_DP5_NX + i];
        r[4 * CS_DP5_NX + i] = h * (cs_dp5_d1 * k1[i] + cs_dp5_d3 * k3[i] + cs_dp5_d4 * k4[i] + cs_dp5_d5 * k5[i]
                                    + cs_dp5_d6 * k6[i] + cs_dp5_d7 * k7[i]);
        x[i] = y1[i];
        k1[i] = k7[i];
      }
      c[7] = s;
      c[10] = h;
      s += h;
      c[0] = s;
      if (c[11] && hnew > h) hnew = h;      /* no increase right after a rejection */
      c[11] = 0;
      c[1] = hnew;
    } else {
      fac = fac11 / cs_dp5_safe;
      c[1] = h / (fac < 1.0 / cs_dp5_fac_min ? fac : 1.0 / cs_dp5_fac_min);
      c[3] += 1;
      c[11] = 1; c[12] = 0;
    }
  }
  goto done;
rhs_failed:
  c[5] = 3; c[6] = s;
done:
  if (!xo) return;
  if (c[5] != 0) {
    for (i = 0; i < CS_DP5_NX; ++i) xo[i] = NAN;
  } else if (s_out >= c[0] || c[10] <= 0) {
    for (i = 0; i < CS_DP5_NX; ++i) xo[i] = x[i];
  } else {                                   /* dense output inside the last step */
    theta = (s_out - c[7]) / c[10];
    theta1 = 1.0 - theta;
    for (i = 0; i < CS_DP5_NX; ++i)
      xo[i] = r[i] + theta * (r[CS_DP5_NX + i] + theta1 * (r[2 * CS_DP5_NX + i] + theta
              * (r[3 * CS_DP5_NX + i] + theta1 * r[4 * CS_DP5_NX + i])));
  }
}

/* One block of CS_DP5_NK output times (a shorter grid repeats its last time). */
CASADI_SYMBOL_EXPORT int cablesys_dopri5(const casadi_real** arg, casadi_real** res, casadi_int* iw, casadi_real* w,
                                         int mem) {
  casadi_int i, k;
  for (i = 0; i < CS_DP5_NC; ++i) w[i] = arg[0] ? arg[0][i] : 0;
  for (k = 0; k < CS_DP5_NK; ++k)
    cs_dp5_advance(arg[1] ? arg[1][k] : 0, arg[2], arg[3], arg[4], res[1] ? res[1] + k * CS_DP5_NX : 0,
                   arg + 5, res + 2, iw, w);
  if (res[0]) for (i = 0; i < CS_DP5_NC; ++i) res[0][i] = w[i];
  return 0;
}

CASADI_SYMBOL_EXPORT casadi_int cablesys_dopri5_n_in(void) { return 5; }
CASADI_SYMBOL_EXPORT casadi_int cablesys_dopri5_n_out(void) { return 2; }

CASADI_SYMBOL_EXPORT const char* cablesys_dopri5_name_in(casadi_int i) {
  switch (i) {
    case 0: return "carry_in";
    case 1: return "s_out";     /* CS_DP5_NK output times */
    case 2: return "p";
    case 3: return "tol";
    case 4: return "atol";
    default: return 0;
  }
}

CASADI_SYMBOL_EXPORT const char* cablesys_dopri5_name_out(casadi_int i) {
  switch (i) {
    case 0: return "carry_out";
    case 1: return "x";
    default: return 0;
  }
}

CASADI_SYMBOL_EXPORT const casadi_int* cablesys_dopri5_sparsity_in(casadi_int i) {
  switch (i) {
    case 0: return cs_dp5_sp_carry;
    case 1: return cs_dp5_sp_times;
    case 2: return cs_dp5_sp_p;
    case 3: return cs_dp5_sp_tol;
    case 4: return cs_dp5_sp_x;
    default: return 0;
  }
}

CASADI_SYMBOL_EXPORT const casadi_int* cablesys_dopri5_sparsity_out(casadi_int i) {
  switch (i) {
    case 0: return cs_dp5_sp_carry;
    case 1: return cs_dp5_sp_xs;
    default: return 0;
  }
}

CASADI_SYMBOL_EXPORT int cablesys_dopri5_work(casadi_int* sz_arg, casadi_int* sz_res, casadi_int* sz_iw,
                                              casadi_int* sz_w) {
  casadi_int n_arg = 0, n_res = 0, n_iw = 0, n_w = 0;   /* the right-hand side's, after ours */
  CS_DP5_RHS_WORK(&n_arg, &n_res, &n_iw, &n_w);
  if (sz_arg) *sz_arg = 5 + (n_arg > 5 ? n_arg : 5);
  if (sz_res) *sz_res = 2 + (n_res > 4 ? n_res : 4);
  if (sz_iw) *sz_iw = n_iw;
  if (sz_w) *sz_w = CS_DP5_NW + n_w;
  return 0;
}
