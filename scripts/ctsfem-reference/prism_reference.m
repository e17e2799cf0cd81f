% CTSFEM's clustered two-stage prism (Software_Verification_and_Examples/3Clustered_tensegrity/
% dynamic/5CTS_prism_dynamic, main_CTS_prism_dynamics.m, its "Step 1: statics"), rebuilt here
% from its data with CTSFEM's own Function_library: 12 nodes on three levels 1 m apart,
% 8 bars, 20 strings, the four vertical strings of the two stages joined in pairs through
% the middle nodes (4 clusters), the bottom four nodes pinned; its prestress design (the
% first cluster and the bottom ring at 100 N), its sizing (solid bars, c_b = 1, c_s = 0.1;
% the middle ring's area cut to 1e-8 m^2) and its nonlinear statics: the four clusters
% shortened by 0.7 m each, ramped over 20 substeps (static_solver_CTS; its result then
% polished by polish_static.m: the same solver without line search, to 1e-9 N; ./run).
% One choice differs from the example's script: material{2} = 1 (strings slacken), as this
% toolkit's strings and clusters are tension-only (no string goes slack on this path: the
% final forces are all tensions, checked by tests/ctsfem_reference.rs).
% Called by ./run with OUT set; no plotting.

global Eb Es
[consti_data, Eb, Es, sigmab, sigmas, rho_b, rho_s] = material_lib('Steel_Q345', 'Steel_string');
material = {'linear_elastic', 1};

N = [[-1 1 0; 1 1 0; 1 -1 0; -1 -1 0]', [-1 0 1; 0 1 1; 1 0 1; 0 -1 1]', ...
     [-1 -1 2; -1 1 2; 1 1 2; 1 -1 2]'];
bars = [1 8; 4 7; 3 6; 2 5; 7 10; 6 9; 5 12; 8 11];
strings = [4 8; 3 7; 2 6; 1 5; 8 12; 7 11; 6 10; 5 9; 1 4; 4 3; 3 2; 2 1; 5 8; 8 7; 7 6; 6 5; ...
           9 12; 12 11; 11 10; 10 9];
C_b = tenseg_ind2C(bars, N);
C_s = tenseg_ind2C(strings, N);
C = [C_b; C_s];
[ne, nn] = size(C);
pinned = (1:4)';
[Ia, Ib, a, b] = tenseg_boundary(pinned, pinned, pinned, nn);
S = tenseg_str_gp({[9, 13], [10, 14], [11, 15], [12, 16]}, C)';

[A_1, A_1c, A_1a, A_1ac, A_2, A_2c, A_2a, A_2ac, l, l_c] = tenseg_equilibrium_matrix_CTS(N, C, S, Ia);
[U1, U2, V1, V2, S1] = tenseg_svd(A_2ac);
w0a = zeros(numel(a), 1);
[q_c, t_c, q, t] = tenseg_prestress_design_f(S, l, l_c, A_2ac, V2, w0a, [9, 13:16]', 1e2 * ones(5, 1));
index_b = find(t_c < 0);
index_s = setdiff(1:size(S, 1), index_b);
[A_b, A_s, A_c, A, r_b, r_s, r_gp, radius, E_c, l0_c, rho, mass_c] = tenseg_minimass(t_c, l_c, ...
    eye(size(S, 1)), sigmas, sigmab, Eb, Es, index_b, index_s, 1, 0.1, rho_b, rho_s, 6e-3, 0);
A_c(17:20) = 1e-8;
E = S' * E_c; A = S' * A_c;
l0 = (t + E .* A) .\ (E .* A .* l);
l0_c = S * l0;

dl0_c = zeros(size(l0_c)); dl0_c(9:12) = -0.7;
substep = 20;
data = struct();
data.N = N; data.C = C; data.ne = ne; data.nn = nn; data.Ia = Ia; data.Ib = Ib; data.S = S;
data.E = E_c; data.A = A_c; data.index_b = index_b; data.index_s = index_s;
data.consti_data = consti_data; data.material = material;
data.w_t = zeros(3 * nn, substep);
data.dnb_t = zeros(numel(b), substep);
data.l0_t = l0_c + dl0_c * linspace(0, 1, substep);
data.substep = substep;
out_s = static_solver_CTS(data);
out_p = polish_static(data, out_s);

member_cluster = zeros(ne, 1);
rows_cl = find(sum(S, 2) > 1);
for k = 1:numel(rows_cl)
  member_cluster(S(rows_cl(k), :) > 0) = k;
end
ends = zeros(ne, 2);
for k = 1:ne
  ends(k, :) = [find(C(k, :) == -1), find(C(k, :) == 1)];
end

r = struct();
r.source = 'CTSFEM 13ac83f, 3Clustered_tensegrity/dynamic/5CTS_prism_dynamic (prism_reference.m)';
r.octave = version();
r.youngs_modulus_bar = Eb; r.youngs_modulus_string = Es;
r.nodes_initial = N;
r.member_start = ends(:, 1); r.member_end = ends(:, 2);
r.member_is_bar = double(t < 0);
r.member_cluster = member_cluster;
r.pinned_nodes = pinned;
r.element_members_first = arrayfun(@(k) find(S(k, :), 1), (1:size(S, 1))');
r.element_is_bar = double(t_c < 0);
r.element_area = A_c; r.element_youngs = E_c; r.element_rest_length = l0_c;
r.element_prestress = t_c;
r.element_rest_length_static = l0_c + dl0_c;
r.nodes_static = out_p.N;
r.element_force_static = pinv(S') * out_p.t_out(:, end);
r.residual_static_ctsfem = out_s.Fpn_out(end);   % CTSFEM's solver as it is
r.residual_static = out_p.Fpn_out(end);          % after polishing (polish_static.m)
ctsfem_json(fullfile(OUT, 'prism.json'), r);
