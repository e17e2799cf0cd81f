% CTSFEM's clustered T-bar (Software_Verification_and_Examples/3Clustered_tensegrity/dynamic/
% 4CTS_Tbar_dynamic), rebuilt here from its data and run with CTSFEM's own Function_library:
% its prestress design and member sizing, its nonlinear statics (static_solver_CTS: the
% cluster's and two strings' rest lengths changed) and its dynamics (dynamic_solver_CTS,
% ode4_CTS) after a sudden shortening of the cluster.
% Called by ./run with OUT (the output folder) set; no plotting.
%
% Choices that differ from the example's script (each so that the two codes solve the same
% problem; docs/notes/CTSFEM.md):
%  - statics: material{2} = 1 (strings slacken), as this toolkit's strings and clusters are
%    tension-only; the example's ramp (10 substeps) and hold (10 substeps), then CTSFEM's
%    result polished (polish_static.m: its solver without line search, to 1e-9 N; ./run);
%  - dynamics: the cluster's rest length shortened by 0.1 m at t = 0 (a step, not the
%    example's ramp: this toolkit's elastic dynamics has no rest-length actuation; the
%    strings are not lengthened, which would slacken them at once, and CTSFEM's dynamics
%    cannot run a slack member: its mass update divides 0 by 0); material{2} = 0 there, and
%    the strings are checked to stay taut all along (min_string_force_dynamic); no damping;
%    the cluster massless (data.rho zero on its segments: this toolkit's clusters carry no
%    mass); bars and strings keep their mass rho A l0 and CTSFEM's consistent mass matrix;
%    RK4 (ode4_CTS) at the example's dt = 1e-4 s to tf = 0.2 s.

global Eb Es
[consti_data, Eb, Es, sigmab, sigmas, rho_b, rho_s] = material_lib('Steel_Q345', 'Steel_string');
material = {'linear_elastic', 1};

N = [0 0 0; 1 2 0; 2 0 0; 1 -2 0]';
C_b = tenseg_ind2C([1 3; 2 4], N);
C_s = tenseg_ind2C([1 2; 2 3; 3 4; 4 1], N);
C = [C_b; C_s];
[ne, nn] = size(C);
[Ia, Ib, a, b] = tenseg_boundary([], [], (1:nn)', nn);   % planar: every node held in z
S = tenseg_str_gp({[3, 4]}, C)';                        % strings 1-2 and 2-3: one cluster

% prestress: the clustered self-stress scaled to -100 N in bar 1
[A_1, A_1c, A_1a, A_1ac, A_2, A_2c, A_2a, A_2ac, l, l_c] = tenseg_equilibrium_matrix_CTS(N, C, S, Ia);
[U1, U2, V1, V2, S1] = tenseg_svd(A_2ac);
w0a = zeros(numel(a), 1);
[q_c, t_c, q, t] = tenseg_prestress_design_f(S, l, l_c, A_2ac, V2, w0a, 1, -1e2);

% sizing (the example's coefficients: solid bars, c_b = c_s = 0.1)
index_b = find(t_c < 0);
index_s = setdiff(1:size(S, 1), index_b);
[A_b, A_s, A_c, A, r_b, r_s, r_gp, radius, E_c, l0_c, rho, mass_c] = tenseg_minimass(t_c, l_c, ...
    eye(size(S, 1)), sigmas, sigmab, Eb, Es, index_b, index_s, 0.1, 0.1, rho_b, rho_s, 6e-3, 0);
E = S' * E_c;
A = S' * A_c;
l0 = (t + E .* A) .\ E .* A .* l;    % rest length of every segment
l0_c = S * l0;                         % of every clustered element (the cluster: their sum)

% ---- statics: the example's rest-length change, ramped over 10 substeps then held
dl0_c = zeros(size(l0_c)); dl0_c([3, 4, 5]) = [-2, 0.5, 0.5];
substep = 20;
ramp = [linspace(1/10, 1, 10), ones(1, 10)];
data = struct();
data.N = N; data.C = C; data.ne = ne; data.nn = nn; data.Ia = Ia; data.Ib = Ib; data.S = S;
data.E = E_c; data.A = A_c; data.index_b = index_b; data.index_s = index_s;
data.consti_data = consti_data; data.material = material;
data.w_t = zeros(3 * nn, substep);
data.dnb_t = zeros(numel(b), substep);
data.l0_t = l0_c + dl0_c * ramp;
data.substep = substep;
out_s = static_solver_CTS(data);
out_p = polish_static(data, out_s);
N_static = out_p.N;
% the structure floats in its plane: report it in the frame where node 1 is at the origin
% and node 3 on the +x axis (the frame of the toolkit's scene, which holds node 1 in x, y
% and node 3 in y to remove the rigid motions; they carry no force)
d = N_static(:, 3) - N_static(:, 1);
c = d(1) / norm(d(1:2)); s = d(2) / norm(d(1:2));
Rz = [c s 0; -s c 0; 0 0 1];
N_static_frame = Rz * (N_static - N_static(:, 1));
l_s = sqrt(sum((N_static * C').^2))';
t_static_c = pinv(S') * out_p.t_out(:, end);   % one force per clustered element

% ---- dynamics: a step change of the rest lengths by dl0_c / 5 at t = 0
dt = 1e-4; tf = 0.2;
tspan = 0:dt:tf;
rho_e = rho_b * ones(ne, 1); rho_e([3, 4]) = 0;   % bars and strings 7870 kg/m^3, cluster massless
mass = rho_e .* A .* l0;
dd = struct();
dd.N = N; dd.C = C; dd.ne = ne; dd.nn = nn; dd.Ia = Ia; dd.Ib = Ib; dd.S = S;
dd.E = E_c; dd.A = A_c; dd.index_b = index_b; dd.index_s = index_s;
dd.consti_data = consti_data; dd.material = {'linear_elastic', 0};
dd.w_t = zeros(3 * nn, 1);
dd.dnb_t = zeros(numel(b), 1); dd.dnb_d_t = zeros(numel(b), 1); dd.dnb_dd_t = zeros(numel(b), 1);
dl0_dyn = zeros(size(l0_c)); dl0_dyn(3) = -0.1;
dd.l0_t = l0_c + dl0_dyn;
dd.n0a_d = zeros(numel(a), 1);
dd.M = tenseg_mass_matrix(mass, C, 0); dd.D = zeros(3 * nn);
dd.rho = rho_e;
dd.tf = tf; dd.dt = dt; dd.tspan = tspan;
dd.out_tspan = tspan(1:10:end);    % every 1 ms (for the slack check)
out_d = dynamic_solver_CTS(dd);
% the state after the last step (ode4_CTS's own n_t at tf is its last stage's)
Ya = out_d.Ya_t;
global f n
samples = [];
for k = 1:500:numel(tspan)
  tenseg_dyn_x_xdot_CTS(tspan(k), Ya(:, k), dd);
  samples(end + 1).t = tspan(k);
  samples(end).n = reshape(n, 3, []);
  samples(end).f = pinv(S') * f;
end
tenseg_dyn_x_xdot_CTS(tspan(end), Ya(:, end), dd);
N_dyn = reshape(n, 3, []);
f_dyn = pinv(S') * f;

r = struct();
r.source = 'CTSFEM 13ac83f, 3Clustered_tensegrity/dynamic/4CTS_Tbar_dynamic (tbar_reference.m)';
r.octave = version();
r.youngs_modulus_bar = Eb; r.youngs_modulus_string = Es;
r.density = rho_b;
r.area = A_c;                    % per clustered element: bar 1, bar 2, cluster, string 3-4, string 4-1
r.rest_length = l0_c;            % the same order
r.axial_stiffness = E_c .* A_c ./ l0_c;
r.mass = mass;                   % per segment (bars, strings 1-2, 2-3, 3-4, 4-1)
r.prestress = t_c;
r.nodes_initial = N;
r.rest_length_static = l0_c + dl0_c;
r.nodes_static = N_static_frame;
r.force_static = t_static_c;
r.residual_static_ctsfem = out_s.Fpn_out(end);   % CTSFEM's solver as it is
r.residual_static = out_p.Fpn_out(end);          % after polishing (polish_static.m)
r.rest_length_dynamic = dd.l0_t;
r.dt = dt; r.t_end = tf;
r.nodes_dynamic = N_dyn;
r.force_dynamic = f_dyn;
r.min_string_force_dynamic = min(min(out_d.t_t(3:6, :)));
for k = 1:numel(samples)
  r.(sprintf('nodes_dynamic_t%03d', round(1000 * samples(k).t))) = samples(k).n;
  r.(sprintf('force_dynamic_t%03d', round(1000 * samples(k).t))) = samples(k).f;
end
ctsfem_json(fullfile(OUT, 'tbar.json'), r);
