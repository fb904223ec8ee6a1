/* cablesys explicit Runge-Kutta pairs with error control and dense output, a block of output
 * times per call, in CasADi's external-function C API (see cablesys/time_domain/explicit_rk.py).
 * One driver, two embedded pairs (the file keeps its first pair's name):
 *   CS_ERK_METHOD 1  DOPRI5: Dormand & Prince (1980) 5(4), 7 stages, FSAL (6 new evaluations a step)
 *   CS_ERK_METHOD 2  BS3:    Bogacki & Shampine (1989) 3(2), 4 stages, FSAL (3 new evaluations a step)
 * A pair is a small table (stages S, a_ij, c_i, error weights e_i = b_i - b^_i, the order of the
 * propagated solution for the starting step, the order of the embedded one for the step exponent,
 * the PI beta, and optional dense-output weights d_i); everything else is shared.
 *
 * Appended by cablesys.time_domain.explicit_rk to the C that CasADi's CodeGenerator generates for the
 * model's relative-time ODE, after these definitions (prepended by the Python side):
 *   CS_ERK_METHOD    the pair (1 or 2, above)
 *   CS_ERK_NAME      the exported driver's name (cablesys_dopri5, cablesys_rk23)
 *   CS_ERK_NX        number of states
 *   CS_ERK_NP        length of the integrator's p (the model's p, then t0 and h)
 *   CS_ERK_NK        output times per call (a block; the x output is NX x NK)
 *   CS_ERK_RHS       the generated right-hand side, (s, x, z, p, u) -> (x', alg, quad, zero)
 *   CS_ERK_RHS_WORK  its work-size function
 *
 * Methods: Dormand & Prince (1980), "A family of embedded Runge-Kutta formulae", J. Comput. Appl.
 * Math. 6(1), 19-26 (coefficients a_ij, c_i, b_i; first same as last); Bogacki & Shampine (1989),
 * "A 3(2) pair of Runge-Kutta formulas", Appl. Math. Lett. 2(4), 321-325 (the pair of MATLAB's
 * ode23 and SciPy's RK23). Error estimate, PI step control, initial step and dense output as in
 * Hairer, Norsett & Wanner, Solving Ordinary Differential Equations I (2nd ed. 1993), sec. II.4
 * (error norm eq. 4.11, step factor eq. 4.13 with the exponent 1/(q+1) of an order-q estimate,
 * initial step "starting step size" algorithm with the method's order), II.5 (Table 5.2), II.6
 * (dense output: the cubic Hermite interpolant of (x_n, f_n, x_n+1, f_n+1), third order, which
 * is BS3's (as SciPy's RK23), plus for DOPRI5 the quartic correction with the coefficients d_i of
 * Hairer's DOPRI5 code, CONTD5), and Hairer & Wanner, Solving ODEs II, sec. IV.2 (the PI
 * controller; beta = 0.04 as in DOPRI5, 0.08 for BS3, measured below).
 *
 * The carry (input 0 -> output 0) holds the integrator between output times and calls:
 *   [0] s        current (relative) time       [6]  s_fail   time of a failure
 *   [1] h        proposed next step (0: pick)  [7]  s_old    start of the last accepted step
 *   [2] accepted steps                          [8]  err_old  previous error norm (PI control)
 *   [3] rejected steps                          [9]  k1 valid (first same as last)
 *   [4] right-hand-side evaluations             [10] h_last   length of the last accepted step
 *   [5] status (0 ok, 1 too much work, 2 step too small,   [11] last step rejected
 *       3 step too small, the last rejection non-finite,   [12] the last rejection was for non-finite stages
 *       4 paused: the call's budget of attempted steps tol[2] is used up; not a failure, the caller
 *       resumes from the last output reached)
 *   Once the status is set, the remaining output times of the call are NaN and cost nothing.
 *   then x (NX), k1 = f(s, x) (NX), the 5 NX dense-output coefficients of the last accepted step
 *   (the fifth is 0 for a pair without d_i: the Hermite cubic).
 */
#define CS_ERK_HEAD 13
#define CS_ERK_NC (CS_ERK_HEAD + 7 * CS_ERK_NX)

/* the pairs' coefficients (DOPRI5's are parsed by tests/test_dopri5.py, BS3's by tests/test_explicit_rk.py) */
#if CS_ERK_METHOD == 1
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
#define CS_ERK_S 7                 /* stages; the last is f(s + h, x_n+1) (first same as last) */
#define CS_ERK_P 5                 /* order of the propagated solution (starting step) */
#define CS_ERK_Q 4                 /* order of the embedded solution: step factor err^(1/(Q+1)) */
#define CS_ERK_BETA 0.04           /* PI control (DOPRI5's default) */
#define CS_ERK_C {0, cs_dp5_c2, cs_dp5_c3, cs_dp5_c4, cs_dp5_c5, 1, 1}
#define CS_ERK_A {{0}, {cs_dp5_a21}, {cs_dp5_a31, cs_dp5_a32}, {cs_dp5_a41, cs_dp5_a42, cs_dp5_a43}, \
                  {cs_dp5_a51, cs_dp5_a52, cs_dp5_a53, cs_dp5_a54}, \
                  {cs_dp5_a61, cs_dp5_a62, cs_dp5_a63, cs_dp5_a64, cs_dp5_a65}, \
                  {cs_dp5_a71, 0, cs_dp5_a73, cs_dp5_a74, cs_dp5_a75, cs_dp5_a76}}
#define CS_ERK_E {cs_dp5_e1, 0, cs_dp5_e3, cs_dp5_e4, cs_dp5_e5, cs_dp5_e6, cs_dp5_e7}
#define CS_ERK_D {cs_dp5_d1, 0, cs_dp5_d3, cs_dp5_d4, cs_dp5_d5, cs_dp5_d6, cs_dp5_d7}
#elif CS_ERK_METHOD == 2
/* Bogacki & Shampine (1989), the 3(2) pair: c, a_ij, b = a_4j (first same as last); b^ = (7/24, 1/4,
   1/3, 1/8) the embedded 2nd-order weights, e = b - b^ */
static const casadi_real cs_bs3_c2 = 1.0 / 2, cs_bs3_c3 = 3.0 / 4;
static const casadi_real cs_bs3_a21 = 1.0 / 2;
static const casadi_real cs_bs3_a32 = 3.0 / 4;
static const casadi_real cs_bs3_a41 = 2.0 / 9, cs_bs3_a42 = 1.0 / 3, cs_bs3_a43 = 4.0 / 9;
static const casadi_real cs_bs3_e1 = -5.0 / 72, cs_bs3_e2 = 1.0 / 12, cs_bs3_e3 = 1.0 / 9, cs_bs3_e4 = -1.0 / 8;
#define CS_ERK_S 4
#define CS_ERK_P 3
#define CS_ERK_Q 2                 /* step factor err^(1/3) */
#define CS_ERK_BETA 0.08           /* measured on the ramped Dale scene, rtol 1e-3-1e-4: 1.9-2.2k rejections per
                                      9k steps against 2.7-3.0k with 0.04 and 3.5k with 0 (3-7 % fewer evaluations) */
#define CS_ERK_C {0, cs_bs3_c2, cs_bs3_c3, 1}
#define CS_ERK_A {{0}, {cs_bs3_a21}, {0, cs_bs3_a32}, {cs_bs3_a41, cs_bs3_a42, cs_bs3_a43}}
#define CS_ERK_E {cs_bs3_e1, cs_bs3_e2, cs_bs3_e3, cs_bs3_e4}
/* no CS_ERK_D: the dense output is the cubic Hermite interpolant (Hairer et al. II.6) */
#else
#error "CS_ERK_METHOD must be 1 (DOPRI5) or 2 (BS3)"
#endif

/* the stages k_2..k_S, the stage argument and x_n+1 */
#define CS_ERK_NW (CS_ERK_NC + (CS_ERK_S + 1) * CS_ERK_NX)
#define CS_ERK_CAT2(a, b) a##b
#define CS_ERK_CAT(a, b) CS_ERK_CAT2(a, b)
#define CS_ERK_FN(suffix) CS_ERK_CAT(CS_ERK_NAME, suffix)

static const casadi_int cs_erk_sp_carry[3] = {CS_ERK_NC, 1, 1};
static const casadi_int cs_erk_sp_times[3] = {CS_ERK_NK, 1, 1};
static const casadi_int cs_erk_sp_p[3] = {CS_ERK_NP, 1, 1};
static const casadi_int cs_erk_sp_tol[3] = {3, 1, 1};   /* rtol, steps per output, steps per call */
static const casadi_int cs_erk_sp_x[3] = {CS_ERK_NX, 1, 1};
static const casadi_int cs_erk_sp_xs[3] = {CS_ERK_NX, CS_ERK_NK, 1};

/* step control (Hairer et al. II.4, IV.2; DOPRI5 defaults): safety, factor bounds */
static const casadi_real cs_erk_safe = 0.9, cs_erk_fac_min = 0.2, cs_erk_fac_max = 10.0;
static const casadi_real cs_erk_uround = 2.3e-16;

static int cs_erk_isfinite(casadi_real v) { return v - v == 0.0; }

/* out = f(s, x): the generated relative-time ODE (z and u are empty) */
static int cs_erk_f(casadi_real s, const casadi_real* x, const casadi_real* p, casadi_real* out,
                    const casadi_real** arg, casadi_real** res, casadi_int* iw, casadi_real* w) {
  arg[0] = &s; arg[1] = x; arg[2] = 0; arg[3] = p; arg[4] = 0;
  res[0] = out; res[1] = 0; res[2] = 0; res[3] = 0;
  return CS_ERK_RHS(arg, res, iw, w, 0);
}

/* RMS of v_i / (atol_i + rtol max(|x_i|, |y_i|)) (Hairer et al. eq. II.4.11) */
static casadi_real cs_erk_norm(const casadi_real* v, const casadi_real* x, const casadi_real* y,
                               casadi_real rtol, const casadi_real* atol) {
  casadi_real sum = 0, sk, ax, ay;
  casadi_int i;
  for (i = 0; i < CS_ERK_NX; ++i) {
    ax = fabs(x[i]);
    ay = y ? fabs(y[i]) : ax;
    sk = (atol ? atol[i] : 0) + rtol * (ax > ay ? ax : ay);
    sum += (v[i] / sk) * (v[i] / sk);
  }
  return sqrt(sum / CS_ERK_NX);
}

/* out = h sum_l w_l K_l (zero weights skipped) */
static void cs_erk_combine(casadi_real h, const casadi_real* wts, casadi_int n, casadi_real* const* K,
                           casadi_real* out) {
  casadi_int i, l;
  casadi_real acc;
  for (i = 0; i < CS_ERK_NX; ++i) {
    acc = 0;
    for (l = 0; l < n; ++l)
      if (wts[l] != 0) acc += wts[l] * K[l][i];
    out[i] = h * acc;
  }
}

/* Advance the carry c (in w) to s_out, at most tol[1] attempted steps, and write x(s_out) to xo; stop
   (status 4) when the call has attempted tol[2] steps (tol[2] <= 0: no limit), so that one call
   costs a bounded time and the caller can look for an interrupt between calls. */
static void cs_erk_advance(casadi_real s_out, const casadi_real* p, const casadi_real* tol, const casadi_real* atol,
                           casadi_real* xo, const casadi_real** sub_arg, casadi_real** sub_res, casadi_int* iw,
                           casadi_real* w) {
  const casadi_real A[CS_ERK_S][CS_ERK_S] = CS_ERK_A, cs[CS_ERK_S] = CS_ERK_C, E[CS_ERK_S] = CS_ERK_E;
#ifdef CS_ERK_D
  const casadi_real D[CS_ERK_S] = CS_ERK_D;
#endif
  casadi_real* c = w;                       /* the carry */
  casadi_real *x = c + CS_ERK_HEAD, *k1 = x + CS_ERK_NX, *r = k1 + CS_ERK_NX;
  casadi_real* K[CS_ERK_S];                 /* K[0] = k1 (carried), K[1..S-1] the new stages */
  casadi_real* yt = w + CS_ERK_NC + (CS_ERK_S - 1) * CS_ERK_NX;
  casadi_real* y1 = yt + CS_ERK_NX;
  casadi_real* kl;                          /* the last stage f(s + h, x_n+1) */
  casadi_real* rw = w + CS_ERK_NW;          /* the right-hand side's work */
  casadi_real rtol = tol ? tol[0] : 0;
  casadi_int max_steps = tol ? (casadi_int)tol[1] : 0, taken = 0, i, j;
  casadi_real call_budget = tol ? tol[2] : 0;
  casadi_real s, h, err, fac, fac11, hnew, theta, theta1, span, bound, sk, dnf, dny, der2, h1;
  K[0] = k1;
  for (j = 1; j < CS_ERK_S; ++j) K[j] = w + CS_ERK_NC + (j - 1) * CS_ERK_NX;
  kl = K[CS_ERK_S - 1];
  if (max_steps <= 0) max_steps = 100000;
  s = c[0];
  if (c[5] != 0) goto done;                 /* failed or paused earlier in this call */
  if (!c[9]) {                              /* k1 = f(s, x) unless carried over (FSAL) */
    if (cs_erk_f(s, x, p, k1, sub_arg, sub_res, iw, rw)) { c[5] = 3; c[6] = s; goto done; }
    c[4] += 1;
    c[9] = 1;
  }
  span = fabs(s_out - s) > 0 ? fabs(s_out - s) : 1.0;
  if (c[1] <= 0 && s < s_out) {            /* starting step (Hairer et al. II.4, "starting step size") */
    dnf = 0; dny = 0;
    for (i = 0; i < CS_ERK_NX; ++i) {
      sk = (atol ? atol[i] : 0) + rtol * fabs(x[i]);
      dnf += (k1[i] / sk) * (k1[i] / sk);
      dny += (x[i] / sk) * (x[i] / sk);
    }
    h = (dnf <= 1e-10 || dny <= 1e-10) ? 1e-6 : 0.01 * sqrt(dny / dnf);
    if (h > span) h = span;
    for (i = 0; i < CS_ERK_NX; ++i) yt[i] = x[i] + h * k1[i];
    if (cs_erk_f(s + h, yt, p, K[1], sub_arg, sub_res, iw, rw)) { c[5] = 3; c[6] = s; goto done; }
    c[4] += 1;
    for (i = 0; i < CS_ERK_NX; ++i) K[1][i] -= k1[i];
    der2 = cs_erk_norm(K[1], x, 0, rtol, atol) * sqrt((casadi_real)CS_ERK_NX) / h;
    if (!(der2 > sqrt(dnf))) der2 = sqrt(dnf);
    h1 = der2 <= 1e-15 ? (1e-6 > h * 1e-3 ? 1e-6 : h * 1e-3) : pow(0.01 / der2, 1.0 / CS_ERK_P);
    h = 100 * h < h1 ? 100 * h : h1;
    if (!(h > 0) || !cs_erk_isfinite(h)) h = 1e-6 * span;
    c[1] = h;
  }
  while (s < s_out) {
    h = c[1];
    bound = fabs(s) > fabs(s_out) ? fabs(s) : fabs(s_out);
    if (taken >= max_steps) { c[5] = 1; c[6] = s; goto done; }
    if (call_budget > 0 && c[2] + c[3] >= call_budget) { c[5] = 4; c[6] = s; goto done; }
    if (0.1 * h <= bound * cs_erk_uround) { c[5] = c[12] ? 3 : 2; c[6] = s; goto done; }
    ++taken;
    /* stages k_j = f(s + c_j h, x + h sum_l a_jl k_l); the last one's argument is x_n+1 (FSAL) */
    for (j = 1; j < CS_ERK_S; ++j) {
      casadi_real* yj = j == CS_ERK_S - 1 ? y1 : yt;
      cs_erk_combine(h, A[j], j, K, yj);
      for (i = 0; i < CS_ERK_NX; ++i) yj[i] += x[i];
      if (cs_erk_f(s + cs[j] * h, yj, p, K[j], sub_arg, sub_res, iw, rw)) goto rhs_failed;
    }
    c[4] += CS_ERK_S - 1;
    /* local error estimate h sum (b_i - b^_i) k_i (Hairer et al. eq. II.4.11 norm) */
    cs_erk_combine(h, E, CS_ERK_S, K, yt);
    err = cs_erk_norm(yt, x, y1, rtol, atol);
    if (!cs_erk_isfinite(err)) {             /* a non-finite stage: retry with a much smaller step */
      c[3] += 1; c[11] = 1; c[12] = 1;
      c[1] = h * cs_erk_fac_min;
      continue;
    }
    /* PI step-size control (Hairer & Wanner, Solving ODEs II, sec. IV.2; DOPRI5): h_new = h / fac,
       fac = err^(1/(q+1) - 0.75 beta) / err_old^beta / safe, bounded to [1/fac_max, 1/fac_min] */
    fac11 = pow(err, 1.0 / (CS_ERK_Q + 1) - CS_ERK_BETA * 0.75);
    if (err <= 1.0) {
      fac = fac11 / pow(c[8] > 0 ? c[8] : 1e-4, CS_ERK_BETA) / cs_erk_safe;
      fac = fac < 1.0 / cs_erk_fac_max ? 1.0 / cs_erk_fac_max : (fac > 1.0 / cs_erk_fac_min ? 1.0 / cs_erk_fac_min : fac);
      hnew = h / fac;
      c[8] = err > 1e-4 ? err : 1e-4;
      c[2] += 1;
      /* dense output of this step (Hairer et al. II.6): the Hermite cubic r0..r3 of (x_n, k1, x_n+1, kl),
         plus DOPRI5's quartic term r4 (CONTD5) */
#ifdef CS_ERK_D
      cs_erk_combine(h, D, CS_ERK_S, K, r + 4 * CS_ERK_NX);
#else
      for (i = 0; i < CS_ERK_NX; ++i) r[4 * CS_ERK_NX + i] = 0;
#endif
      for (i = 0; i < CS_ERK_NX; ++i) {
        r[i] = x[i];
        r[CS_ERK_NX + i] = y1[i] - x[i];
        r[2 * CS_ERK_NX + i] = h * k1[i] - r[CS_ERK_NX + i];
        r[3 * CS_ERK_NX + i] = r[CS_ERK_NX + i] - h * kl[i] - r[2 * CS_ERK_NX + i];
        x[i] = y1[i];
        k1[i] = kl[i];
      }
      c[7] = s;
      c[10] = h;
      s += h;
      c[0] = s;
      if (c[11] && hnew > h) hnew = h;      /* no increase right after a rejection */
      c[11] = 0;
      c[1] = hnew;
    } else {
      fac = fac11 / cs_erk_safe;
      c[1] = h / (fac < 1.0 / cs_erk_fac_min ? fac : 1.0 / cs_erk_fac_min);
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
    for (i = 0; i < CS_ERK_NX; ++i) xo[i] = NAN;
  } else if (s_out >= c[0] || c[10] <= 0) {
    for (i = 0; i < CS_ERK_NX; ++i) xo[i] = x[i];
  } else {                                   /* dense output inside the last step */
    theta = (s_out - c[7]) / c[10];
    theta1 = 1.0 - theta;
    for (i = 0; i < CS_ERK_NX; ++i)
      xo[i] = r[i] + theta * (r[CS_ERK_NX + i] + theta1 * (r[2 * CS_ERK_NX + i] + theta
              * (r[3 * CS_ERK_NX + i] + theta1 * r[4 * CS_ERK_NX + i])));
  }
}

/* One block of CS_ERK_NK output times (a shorter grid repeats its last time). */
CASADI_SYMBOL_EXPORT int CS_ERK_NAME(const casadi_real** arg, casadi_real** res, casadi_int* iw, casadi_real* w,
                                     int mem) {
  casadi_int i, k;
  for (i = 0; i < CS_ERK_NC; ++i) w[i] = arg[0] ? arg[0][i] : 0;
  for (k = 0; k < CS_ERK_NK; ++k)
    cs_erk_advance(arg[1] ? arg[1][k] : 0, arg[2], arg[3], arg[4], res[1] ? res[1] + k * CS_ERK_NX : 0,
                   arg + 5, res + 2, iw, w);
  if (res[0]) for (i = 0; i < CS_ERK_NC; ++i) res[0][i] = w[i];
  return 0;
}

CASADI_SYMBOL_EXPORT casadi_int CS_ERK_FN(_n_in)(void) { return 5; }
CASADI_SYMBOL_EXPORT casadi_int CS_ERK_FN(_n_out)(void) { return 2; }

CASADI_SYMBOL_EXPORT const char* CS_ERK_FN(_name_in)(casadi_int i) {
  switch (i) {
    case 0: return "carry_in";
    case 1: return "s_out";     /* CS_ERK_NK output times */
    case 2: return "p";
    case 3: return "tol";
    case 4: return "atol";
    default: return 0;
  }
}

CASADI_SYMBOL_EXPORT const char* CS_ERK_FN(_name_out)(casadi_int i) {
  switch (i) {
    case 0: return "carry_out";
    case 1: return "x";
    default: return 0;
  }
}

CASADI_SYMBOL_EXPORT const casadi_int* CS_ERK_FN(_sparsity_in)(casadi_int i) {
  switch (i) {
    case 0: return cs_erk_sp_carry;
    case 1: return cs_erk_sp_times;
    case 2: return cs_erk_sp_p;
    case 3: return cs_erk_sp_tol;
    case 4: return cs_erk_sp_x;
    default: return 0;
  }
}

CASADI_SYMBOL_EXPORT const casadi_int* CS_ERK_FN(_sparsity_out)(casadi_int i) {
  switch (i) {
    case 0: return cs_erk_sp_carry;
    case 1: return cs_erk_sp_xs;
    default: return 0;
  }
}

CASADI_SYMBOL_EXPORT int CS_ERK_FN(_work)(casadi_int* sz_arg, casadi_int* sz_res, casadi_int* sz_iw,
                                          casadi_int* sz_w) {
  casadi_int n_arg = 0, n_res = 0, n_iw = 0, n_w = 0;   /* the right-hand side's, after ours */
  CS_ERK_RHS_WORK(&n_arg, &n_res, &n_iw, &n_w);
  if (sz_arg) *sz_arg = 5 + (n_arg > 5 ? n_arg : 5);
  if (sz_res) *sz_res = 2 + (n_res > 4 ? n_res : 4);
  if (sz_iw) *sz_iw = n_iw;
  if (sz_w) *sz_w = CS_ERK_NW + n_w;
  return 0;
}
