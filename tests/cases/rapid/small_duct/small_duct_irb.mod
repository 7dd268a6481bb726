MODULE small_duct_irb
  ! small_duct_irb: part small_duct on robot irb, written by lmdc 0.1.0
  ! source tests/cases/rapid/small_duct/input.lmd, sha256 <sha256 of the source>
  ! 5 layers, 5 paths, 45 points; 58 motion instructions (40 with the laser on) in 3 modules of at most 20
  ! plan: 101.0 mm deposited, 103.2 mm travel; 17.2 s, laser on 11.2 s, dwell 0.0 s; 29.5 kJ; powder 8.60 g
  ! units: mm, deg, mm/s; ao2 = 1 is 4000 W
  ! TCP = laser focus, beam along the tool's +Z axis; clearance 10 mm
  ! positioner: eax_a (tilt) about [1, 0, 0] through [1500, 0, 500] mm, -90 .. 90 deg, 60 deg/s
  ! positioner: eax_b (rotate, at eax_a = 0) about [0, 0, 1] through [1500, 0, 650] mm, -360 .. 360 deg, 90 deg/s
  ! positioner: the work object moves with the mechanical unit STN1; every position is in it
  PERS tooldata lmd_tool := [TRUE,[[0,0,350],[1,0,0,0]],[18,[0,0,160],[1,0,0,0],0,0,0]];
  PERS wobjdata lmd_wobj := [FALSE,FALSE,"STN1",[[0,0,0],[1,0,0,0]],[[0,0,0],[0.707107,0,0,0.707107]]];
  CONST jointtarget lmd_home := [[0,0,0,0,90,0],[0,0,9E+09,9E+09,9E+09,9E+09]];
  CONST speeddata lmd_v1 := [8.834,500,5000,1000];
  CONST speeddata lmd_v2 := [8.622,500,5000,1000];
  CONST speeddata lmd_v3 := [9.152,500,5000,1000];
  CONST speeddata lmd_v4 := [9.391,500,5000,1000];
  CONST speeddata lmd_v5 := [250,500,5000,1000];
  CONST speeddata lmd_v6 := [77.823,500,5000,1000];
  CONST speeddata lmd_v7 := [8.766,500,5000,1000];
  CONST speeddata lmd_v8 := [8.592,500,5000,1000];
  CONST speeddata lmd_v9 := [8.641,500,5000,1000];
  CONST speeddata lmd_v10 := [8.885,500,5000,1000];
  CONST speeddata lmd_v11 := [9.226,500,5000,1000];
  CONST speeddata lmd_v12 := [9.427,500,5000,1000];
  CONST speeddata lmd_v13 := [9.369,500,5000,1000];
  CONST speeddata lmd_v14 := [9.098,500,5000,1000];
  CONST speeddata lmd_v15 := [76.242,500,5000,1000];
  CONST speeddata lmd_v16 := [8.7,500,5000,1000];
  CONST speeddata lmd_v17 := [8.567,500,5000,1000];
  CONST speeddata lmd_v18 := [8.671,500,5000,1000];
  CONST speeddata lmd_v19 := [8.943,500,5000,1000];
  CONST speeddata lmd_v20 := [9.3,500,5000,1000];
  CONST speeddata lmd_v21 := [9.457,500,5000,1000];
  CONST speeddata lmd_v22 := [9.334,500,5000,1000];
  CONST speeddata lmd_v23 := [9.038,500,5000,1000];
  CONST speeddata lmd_v24 := [75.211,500,5000,1000];
  CONST speeddata lmd_v25 := [8.639,500,5000,1000];
  CONST speeddata lmd_v26 := [8.55,500,5000,1000];
  CONST speeddata lmd_v27 := [8.713,500,5000,1000];
  CONST speeddata lmd_v28 := [9.007,500,5000,1000];
  CONST speeddata lmd_v29 := [9.371,500,5000,1000];
  CONST speeddata lmd_v30 := [9.479,500,5000,1000];
  CONST speeddata lmd_v31 := [9.285,500,5000,1000];
  CONST speeddata lmd_v32 := [8.974,500,5000,1000];
  CONST speeddata lmd_v33 := [73.863,500,5000,1000];
  CONST speeddata lmd_v34 := [8.584,500,5000,1000];
  CONST speeddata lmd_v35 := [8.539,500,5000,1000];
  CONST speeddata lmd_v36 := [8.768,500,5000,1000];
  CONST speeddata lmd_v37 := [9.077,500,5000,1000];
  CONST speeddata lmd_v38 := [9.436,500,5000,1000];
  CONST speeddata lmd_v39 := [9.491,500,5000,1000];
  CONST speeddata lmd_v40 := [9.224,500,5000,1000];
  CONST speeddata lmd_v41 := [8.905,500,5000,1000];
  CONST zonedata lmd_z := [FALSE,0.2,0.2,0.2,0.02,0.2,0.02];
  VAR triggdata lmd_on;
  VAR triggdata lmd_off;
  VAR triggdata lmd_power;
  VAR triggdata lmd_on_end;
  VAR triggdata lmd_off_end;
  VAR triggdata lmd_power_end;

  PROC main()
    ConfJ \Off;
    ConfL \Off;
    SetDO do3, 0;
    SetAO ao2, 0;
    MoveAbsJ lmd_home \NoEOffs, v200, fine, lmd_tool \WObj:=lmd_wobj;
    small_duct_irb_m001;
    small_duct_irb_m002;
    small_duct_irb_m003;
    WaitRob \InPos;
    SetDO do3, 0;
    SetAO ao2, 0;
    MoveAbsJ lmd_home \NoEOffs, v200, fine, lmd_tool \WObj:=lmd_wobj;
  ENDPROC
ENDMODULE
