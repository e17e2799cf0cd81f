% CTSFEM's clustered Levy cable dome (Software_Verification_and_Examples/3Clustered_tensegrity/
% static/2cable_dome, main_CTS_cable_dome_trajectory.m at its last deployment rate 0.8),
% rebuilt here from its data with CTSFEM's own Function_library: the geometry
% (N_cable_dome.m of that folder: R = 50 m, p = 12 sectors, m = 2 rings of bars, h = 30 m,
% diagonal strings at 30 deg), the outer ring pinned, 9 symmetry groups, each string group
% split into 3 clustered strings (21 clusters, 4 or 8 segments each), its prestress design
% (the group matrix's 6th column at 20^2/3 kN) and sizing (solid bars, c_b = c_s = 0.1,
% strings slacken).
% Written: the clustered equilibrium matrix's rank and self-stress count, the designed
% prestress (per member and per clustered element, forces and force densities), the rest
% lengths that hold it, and the three smallest eigenvalues of the tangent stiffness there:
% CTSFEM's tenseg_stiff_CTS2, and the exact tangent of CTSFEM's internal force by finite
% differences (ctsfem_internal_force.m). No nonlinear load: the clustered dome is not prestress-stable (its
% tangent stiffness has negative eigenvalues at the designed state; docs/notes/CTSFEM.md),
% and CTSFEM's static_solver_CTS, which shifts the tangent positive definite, runs off to a
% collapsed shape. Called by ./run with OUT set; no plotting.

global Eb Es
[consti_data, Eb, Es, sigmab, sigmas, rho_b, rho_s] = material_lib('Steel_Q345', 'Steel_string');
material = {'linear_elastic', 1};

R = 50; p = 12; m = 2; h = 0.15 * 2 * R; beta = 30 * pi / 180 * ones(m, 1); rate = 0.8;
[N, C_b, C_s, C] = N_cable_dome(R, rate, p, m, h, beta);
[ne, nn] = size(C);
pinned = (5:5:60)';
[Ia, Ib, a, b] = tenseg_boundary(pinned, pinned, pinned, nn);

% symmetry groups (13 members a sector: 2 bars, 11 strings) and the clusters
sec = 13 * (0:p - 1);
pairs = @(i, j) kron(ones(1, p), [i, j]) + 13 * kron(0:p - 1, [1, 1]);
g_whg = 1 + sec; g_nhg = 2 + sec; g_whs = 7 + sec; g_nhs = 12 + sec; g_nhds = 13 + sec;
g_wxs = pairs(5, 6); g_nxs = pairs(10, 11); g_wjs = pairs(3, 4); g_njs = pairs(8, 9);
gr = {g_whg; g_nhg; g_whs; g_nhs; g_nhds; g_wxs; g_nxs; g_wjs; g_njs};
three = @(g) mat2cell(reshape(g, numel(g) / 3, [])', ones(1, 3));
gr2 = [three(g_whs); three(g_nhs); three(g_nhds); three(g_wxs); three(g_nxs); three(g_wjs); three(g_njs)];
Gp = tenseg_str_gp(gr, C);
S = tenseg_str_gp(gr2, C)';

% prestress design on the symmetric groups, as the example does
[A_1a, A_1ag, A_2a, A_2ag, l, l_gp] = tenseg_equilibrium_matrix1(N, C, Gp, Ia);
A_2ac = A_2a * S';
l_c = S * l;
[U1, U2, V1, V2, S1] = tenseg_svd(A_1ag);
w0a = zeros(numel(a), 1);
[q_gp, t_gp, q, t] = tenseg_prestress_design(Gp, l, l_gp, A_1ag, V2, w0a, 6, 20^2 / 3 * 1000);
t_c = pinv(S') * t;
index_b = find(t_c < 0);
index_s = setdiff(1:size(S, 1), index_b);
[A_b, A_s, A_c, A, r_b, r_s, r_gp, radius, E_c, l0_c, rho, mass_c] = tenseg_minimass(t_c, l_c, ...
    eye(size(S, 1)), sigmas, sigmab, Eb, Es, index_b, index_s, 0.1, 0.1, rho_b, rho_s, 6e-3, 0);
E = S' * E_c; A = S' * A_c;
l0 = (t + E .* A) .\ E .* A .* l;
l0_c = S * l0;
% the clustered equilibrium matrix (force variables): its rank and self-stress count
rank_c = rank(A_2ac);
% CTSFEM's tangent stiffness at the designed state (tenseg_stiff_CTS2, as its examples use):
% its three smallest eigenvalues (it adds (t/l) e e' per segment to the exact tangent, see
% docs/notes/CTSFEM.md: they are recorded, not compared)
[Kt_aa, Kg_aa, Ke_aa, K_mode, k_t] = tenseg_stiff_CTS2(Ia, C, q, A_2ac, E_c, A_c, l0_c);
k_t = sort(k_t);
% the exact tangent of CTSFEM's own internal force at that state: central differences
% (step 1e-4 m, 4th order), symmetrised; its three smallest eigenvalues
fd = struct('C', C, 'S', S, 'Ia', Ia, 'Ib', Ib, 'xb', Ib' * N(:), 'l0', l0_c, 'A', A_c, ...
            'consti_data', consti_data, 'index_b', index_b, 'index_s', index_s, 'material', {material});
xa = Ia' * N(:);
hstep = 1e-4;
K_fd = zeros(numel(xa));
for j = 1:numel(xa)
  e = zeros(size(xa)); e(j) = hstep;
  K_fd(:, j) = (-ctsfem_internal_force(xa + 2 * e, fd) + 8 * ctsfem_internal_force(xa + e, fd) ...
                - 8 * ctsfem_internal_force(xa - e, fd) + ctsfem_internal_force(xa - 2 * e, fd)) / (12 * hstep);
end
k_fd = sort(eig((K_fd + K_fd') / 2));

% members in C's order; cluster membership of each member (0: none), 1-based cluster index
% in S's row order
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
r.source = 'CTSFEM 13ac83f, 3Clustered_tensegrity/static/2cable_dome (dome_reference.m)';
r.octave = version();
r.youngs_modulus_bar = Eb; r.youngs_modulus_string = Es;
r.nodes_initial = N;
r.member_start = ends(:, 1); r.member_end = ends(:, 2);   % 1-based nodes, C's row order
r.member_is_bar = double(t < 0);
r.member_cluster = member_cluster;
r.pinned_nodes = pinned;
r.element_members_first = arrayfun(@(k) find(S(k, :), 1), (1:size(S, 1))');
r.element_area = A_c; r.element_youngs = E_c; r.element_rest_length = l0_c;
r.element_prestress = t_c;      % S's row order (bars, strings, clusters by first member)
r.segment_rest_length = l0;     % per member of C
r.prestress = t;                % per member of C
r.rank_clustered = rank_c;
r.self_stress_clustered = size(S, 1) - rank_c;
r.tangent_smallest_eigenvalues_cts2 = k_t(1:3);
r.tangent_smallest_eigenvalues_exact = k_fd(1:3);
r.tangent_asymmetry_exact = norm(K_fd - K_fd', 'fro') / norm(K_fd, 'fro');
r.element_is_bar = double(t_c < 0);
r.element_length = S * l;                    % a cluster: the sum of its segments
r.element_force_density = t_c ./ (S * l);   % tension-positive, per whole member
ctsfem_json(fullfile(OUT, 'dome.json'), r);
