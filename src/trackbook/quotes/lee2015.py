"""Quotes of Lee (2015), covariance matching inside a Kalman search window.

Each original is copied from the paper's text (Korean, or the English abstract); the
translation is beside it. Section numbers are the paper's (I-IV).
"""

from __future__ import annotations

from ._quote import Quote

QUOTES = [
    Quote("lee2015.abstract_rate", "Abstract (English)",
          r"The results show that the tracking rate of 96.3% achieved using the proposed method.",
          "The results show that the tracking rate of 96.3% achieved using the proposed method."),
    Quote("lee2015.abstract_kalman_window", "Abstract (English)",
          r"In order to solve the problem, Kalman filters are used to estimate the area of the "
          r"moving object and covariance matrices as a feature vector are compared with candidate "
          r"regions within the estimated Kalman window.",
          "In order to solve the problem, Kalman filters are used to estimate the area of the "
          "moving object and covariance matrices as a feature vector are compared with candidate "
          "regions within the estimated Kalman window."),
    Quote("lee2015.frame_difference_init", "§I, second paragraph",
          r"먼저 추적을 원하는 물체에 대해 초기 윈도우를 지정해 주어야 하는 문제를 피하기 위해 "
          r"프레임 간 차이를 이용하여 움직이는 영역을 검출한다.",
          "First, to avoid having to give an initial window for the object to be tracked, the "
          "moving region is detected from the difference between frames."),
    Quote("lee2015.features_eq2", "§2.1, eq. 2",
          r"$$f_k = [x \quad y \quad I(x, y) \quad I_x(x, y) \dots] \quad (2)$$",
          "f_k = [x y I(x, y) I_x(x, y) …] (2) — printed with an ellipsis after I_x"),
    Quote("lee2015.features_eq3", "§2.1, eq. 3",
          r"$$f_k^r = [\|x', y'\| \quad I(x, y) \quad I_x(x, y) \dots] \quad (3)$$",
          "f_k^r = [‖x′, y′‖ I(x, y) I_x(x, y) …] (3)"),
    Quote("lee2015.covariance_eq4", "§2.1, eq. 4",
          r"$$C_R = \frac{1}{MN} \sum_{k=1}^{MN} (f_k - \mu_R)(f_k - \mu_R)^T \quad (4)$$",
          "C_R = (1/MN) Σ_k (f_k − μ_R)(f_k − μ_R)ᵀ, k = 1…MN (4)"),
    Quote("lee2015.distance_eq5", "§2.1, eq. 5",
          r"$$\rho(C_i, C_j) = \sqrt{\sum_{k=1}^d \ln^2 \lambda_k(C_i, C_j)} \quad (5)$$",
          "ρ(C_i, C_j) = √(Σ_k ln² λ_k(C_i, C_j)), k = 1…d (5)"),
    Quote("lee2015.eigen_eq6", "§2.1, eq. 6",
          r"$$\lambda_k C_i x_k - C_j x_k = 0 \quad k=1, \dots, d \quad (6)$$",
          "λ_k C_i x_k − C_j x_k = 0, k = 1…d (6)"),
    Quote("lee2015.search_in_prediction", "§2.1, last paragraph",
          r"현재 프레임에서 목표물과 가장 짧은 거리를 가진 영역을 탐색하기 위해 전체 영역을 "
          r"탐색하지 않고 칼만 필터에 의해 예측된 영역 내에서 탐색을 한다.",
          "To find the region with the shortest distance to the target in the current frame, "
          "the search is done inside the region predicted by the Kalman filter rather than over "
          "the whole frame."),
    Quote("lee2015.state_vector", "§2.2, after eq. 8",
          r"$x_k = [x \ y \ \dot{x} \ \dot{y}]^T$ 는 시스템의 상태벡터, $y_k = [x \ y]^T$ 는 "
          r"시스템의 측정벡터이다.",
          "x_k = [x y ẋ ẏ]ᵀ is the state vector of the system and y_k = [x y]ᵀ its measurement "
          "vector."),
    Quote("lee2015.gain_eq11", "§2.2, eq. 11",
          r"$$K_k = P_k^- H^T (HP_k^- H^T + R)^{-1} \quad (11)$$",
          "K_k = P_k⁻ Hᵀ (H P_k⁻ Hᵀ + R)⁻¹ (11)"),
    Quote("lee2015.f_constant_velocity", "§2.2, the matrices",
          r"$$F = \begin{bmatrix} 1 & 0 & 1 & 0 \\ 0 & 1 & 0 & 1 \\ 0 & 0 & 1 & 0 \\ "
          r"0 & 0 & 0 & 1 \end{bmatrix},",
          "F = [[1, 0, 1, 0], [0, 1, 0, 1], [0, 0, 1, 0], [0, 0, 0, 1]] (constant velocity)"),
    Quote("lee2015.q_identity", "§2.2, the matrices",
          r"Q = \begin{bmatrix} 1 & 0 & 0 & 0 \\ 0 & 1 & 0 & 0 \\ 0 & 0 & 1 & 0 \\ "
          r"0 & 0 & 0 & 1 \end{bmatrix}$$",
          "Q = I (the 4 × 4 identity)"),
    Quote("lee2015.r_identity", "§2.2, the matrices",
          r"R = \begin{bmatrix} 1 & 0 \\ 0 & 1 \end{bmatrix}$$",
          "R = I (the 2 × 2 identity)"),
    Quote("lee2015.research_in_window", "§2.3, after Fig. 1",
          r"공분산 행렬은 추적할 이동 물체에 대한 공분산을 계산한 후, 이동 물체의 움직임을 "
          r"추적하기 위해 후보 영역의 공분산을 계산하여 수렴하는지 거리 계산을 한 후 수렴하면 계속 "
          r"추적을 지속하나 수렴하지 않는 경우 칼만 탐색 윈도우 내에서 이동 물체의 영역을 다시 "
          r"찾게 된다.",
          "After computing the covariance of the moving object to be tracked, the candidate "
          "regions' covariances are computed and the distance checked for convergence; if it "
          "converges, tracking continues, and if not, the moving object's region is searched "
          "for again inside the Kalman search window.", kind="reading"),
    Quote("lee2015.hardware", "§III, first paragraph",
          r"본 논문에서 제안한 방법의 실험을 위하여 Windows7, Intel Pentium G2120 @ 3.10GHz "
          r"프로세서 그리고 소니 디지털 캠코더로 촬영한 320×240 크기의 초당 25프레임의 비디오 "
          r"영상과 스마트폰(Galaxy Note II)으로 촬영한 크기의 영상을 사용하였으며, MatLab R2012b "
          r"프로그램으로 구현하였다.",
          "For the experiments of the proposed method, Windows 7 and an Intel Pentium G2120 @ "
          "3.10 GHz processor were used, with 320×240 videos at 25 frames per second shot with "
          "a Sony digital camcorder and videos (size not given) shot with a smartphone (Galaxy "
          "Note II); the method was implemented in MatLab R2012b."),
    Quote("lee2015.frames184", "§III, paragraph on Fig. 3",
          r"그림 3은 공분산 행렬만을 사용하여 이동 물체를 추적한 실험 결과이며, 총 184 프레임의 "
          r"회색 영상으로 변환 후 실험하였다.",
          "Fig. 3 is the result of tracking the moving object with the covariance matrix alone; "
          "the experiment was run after converting a total of 184 frames to grey images."),
    Quote("lee2015.covariance_loses_139", "§III, paragraph on Fig. 3",
          r"이동의 속도가 빨라지는 frame 139~142 프레임에서 영역을 찾지 못하고 추적을 놓치는 "
          r"경우가 발생하였다.",
          "in frames 139–142, where the motion speeds up, it failed to find the region and lost "
          "track."),
    Quote("lee2015.whole_frame_search", "§III, paragraph after Fig. 3",
          r"공분산 행렬은 다른 추적 알고리즘과 달리 지역 최적해 빠지지 않고 전역 최적해를 찾기 "
          r"때문에 일치되는 영역을 발견할 때까지 탐색을 계속해 나가므로 frame 160에서 볼 수 "
          r"있듯이 전 영역을 후보 영역으로 탐색하면서 이동 물체를 찾는다.",
          "Unlike other tracking algorithms, the covariance matrix does not fall into a local "
          "optimum but finds the global optimum, so it keeps searching until it finds a matching "
          "region: as frame 160 shows, it looks for the moving object with the whole frame as "
          "the candidate region."),
    Quote("lee2015.detection_rate_eq14", "§III, eq. 14",
          r"실험의 성능 평가를 위해 영상 프레임 내의 이동 물체의 위치가 정확하게 추정된 검출율은 "
          r"식 (14)와 같다. $$\text{검출율}(\%) = \frac{\text{영역검출영상 프레임수}}"
          r"{\text{전체영상 프레임수}} \times 100 \quad (14)$$",
          "For the evaluation, the detection rate, at which the position of the moving object in "
          "the video frames was estimated correctly, is eq. 14: detection rate (%) = (number of "
          "frames in which the region was detected) / (total number of frames) × 100 (14)."),
    Quote("lee2015.search_rate", "§III, after eq. 14",
          r"평균 탐색률은 탐색의 대상이 되는 전체 영역의 수와 물체의 추정 영역을 찾기 위해 시도한 "
          r"횟수의 비율로 몇 번의 시도 만에 영역을 찾았는지를 나타낸다.",
          "The average search rate is the ratio between the total number of regions subject "
          "to search and the number of attempts made to find the object's estimated region; it "
          "shows after how many attempts the region was found."),
    Quote("lee2015.table1", "§III, Table 1",
          r"miss/total detection rate averaging search rate covariance matrix 21/164 87.1% "
          r"0.134% propose method 6/164 96.3% 0.043%",
          "miss/total, detection rate, averaging search rate — covariance matrix: 21/164, "
          "87.1 %, 0.134 %; proposed method: 6/164, 96.3 %, 0.043 %"),
    Quote("lee2015.table1_redcube", "§III, paragraph after Table 1",
          r"표 1은 고속 이동 물체(RedCube)의 공분산 행렬만을 적용하였을 때와 제안한 방법을 "
          r"적용하였을 때의 이동 물체 추적에 대한 성능 평가 결과이다.",
          "Table 1 is the result of the performance evaluation of moving-object tracking for "
          "the fast-moving object (RedCube) with the covariance matrix alone and with the "
          "proposed method."),
    Quote("lee2015.fig3_cube", "§III, paragraph on Fig. 3",
          r"숫자가 적힌 큐브의 공분산 행렬과 후보 영역의 공분산 행렬을 비교 연산하면서 추적을 "
          r"지속하다가",
          "Tracking went on by comparing the covariance matrix of the cube with numbers written "
          "on it with the covariance matrices of the candidate regions, until"),
    Quote("lee2015.window24", "§III, paragraph after Table 1",
          r"평균 탐색률은 고속의 이동 물체를 24×24의 영역으로 움직이면서 추적했을 때 결과이다.",
          "The average search rate is the result of tracking the fast-moving object by moving a "
          "24×24 region."),
    Quote("lee2015.miss_causes", "§III, paragraph after Table 1",
          r"제안한 방법을 사용하여 추적을 놓친 경우는 일정한 속도로 움직이던 물체가 갑자기 다른 "
          r"방향으로 빠른 속도로 움직일 때, 그리고 고속으로 움직이기 시작한 프레임에서 이동 물체를 "
          r"찾기 위한 연산량의 증가로 이동 물체 영역을 찾기 위한 시간 지연으로 발생하였다.",
          "With the proposed method, track was lost when an object moving at constant speed "
          "suddenly moved fast in another direction, and, in the frames where fast motion "
          "began, through the time delay in finding the object's region caused by the increased "
          "computation."),
    Quote("lee2015.yellowball", "§III, paragraph after Fig. 6",
          r"그림 6은 frame 54~ frame 75에서 빠르게 움직이는 이동 물체(YellowBall)의 추적을 보여주고 "
          r"있다.",
          "Fig. 6 shows the tracking of a fast-moving object (YellowBall) in frames 54–75."),
    Quote("lee2015.init_centre", "§2.3, after Fig. 1",
          r"칼만 필터는 초기 추적할 물체에 대한 탐색 윈도우를 지정해 주기 위해 영상 프레임으로부터 "
          r"움직임이 존재하는 영역을 계산하여 그 중심점을 초기 칼만 탐색 윈도우의 중심 좌표로 정하고 "
          r"칼만 갱신 단계를 거쳐 다음 상태 예측에 사용한다.",
          "To give the search window of the object to track at the start, the Kalman filter "
          "computes the region of the frames where there is motion, takes its centre as the "
          "centre of the initial Kalman search window, and after the Kalman update step uses it "
          "to predict the next state."),
    Quote("lee2015.covariance_search_range", "§2.3, first paragraph",
          r"그러나 이동 물체가 빠르게 방향을 전환하여 움직이는 경우, 공분산 행렬만을 사용한 탐색 "
          r"방법은 탐색 범위 밖으로 목표물이 벗어나므로 후보 영역들이 이동 물체를 찾지 못하므로 전체 "
          r"영역을 다시 탐색하면서 연산해야 하므로 탐색 시간 복잡도가 증가한다.",
          "However, when the moving object turns quickly, with the search that uses the "
          "covariance matrix alone the target leaves the search range, so the candidate regions "
          "do not find the moving object and the whole region must be searched again, which "
          "increases the time complexity of the search."),
    Quote("lee2015.fig2_window", "§III, paragraph on Fig. 2",
          r"그림 2는 칼만 필터에 의해 예측된 탐색 윈도우 영역을 보여준다.",
          "Fig. 2 shows the search-window area predicted by the Kalman filter."),
    Quote("lee2015.yellowball_effective", "§III, paragraph after Fig. 6",
          r"그림 5의 이동 물체(RedCube) 보다 이동 속도가 빠르지 않으나 제안하는 방법에 의한 이동 "
          r"물체 추적이 효과적임을 보여주고 있다.",
          "It moves less fast than the moving object of Fig. 5 (RedCube), but it shows that "
          "tracking the moving object with the proposed method is effective."),
    Quote("lee2015.future_size", "§IV, last sentence",
          r"향후 고속으로 이동하는 사람과 물체의 특성을 고려한 추적 방법에 적용하고 이동 속도 측정 "
          r"및 이동 방향 예측에 따른 칼만 필터의 적용과 이동 물체의 크기에 가변적인 공분산 행렬의 "
          r"적용에 대한 연구가 이뤄져야 할 것이다.",
          "Future work should apply the method to tracking that takes the characteristics of "
          "fast-moving people and objects into account, and study a Kalman filter that follows "
          "measured speed and predicted direction and a covariance matrix that varies with the "
          "size of the moving object."),
]
