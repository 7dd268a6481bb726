MODULE duct_irbp_irb4600
  ! duct_irbp_irb4600: part duct_irbp on robot irb4600, written by lmdc 0.1.0
  ! source examples/duct_irbp.lmd, sha256 <sha256 of the source>
  ! 61 layers, 61 paths, 2497 points; 2728 motion instructions (2436 with the laser on) in 2 modules of at most 2000
  ! plan: 11.58 m deposited, 1.44 m travel; 25 min 49 s, laser on 24 min 27 s, dwell 0.0 s; 3.52 MJ; powder 1.122 kg
  ! units: mm, deg, mm/s; ao1 = 1 is 4000 W
  ! TCP = laser focus, beam along the tool's +Z axis; clearance 10 mm
  ! positioner: eax_a (tilt) about [1, 0, 0] through [1500, 0, 500] mm, -90 .. 90 deg, 60 deg/s
  ! positioner: eax_b (rotate, at eax_a = 0) about [0, 0, 1] through [1500, 0, 650] mm, -360 .. 360 deg, 90 deg/s
  ! positioner: the work object moves with the mechanical unit STN1; every position is in it
  PERS tooldata lmd_tool := [TRUE,[[0,0,350],[1,0,0,0]],[18,[0,0,160],[1,0,0,0],0,0,0]];
  PERS wobjdata lmd_wobj := [FALSE,FALSE,"STN1",[[0,0,0],[1,0,0,0]],[[0,0,0],[0.707107,0,0,0.707107]]];
  CONST jointtarget lmd_home := [[0,0,0,0,90,0],[0,0,9E+09,9E+09,9E+09,9E+09]];
  CONST speeddata lmd_v1 := [7.824,500,5000,1000];
  CONST speeddata lmd_v2 := [7.683,500,5000,1000];
  CONST speeddata lmd_v3 := [7.554,500,5000,1000];
  CONST speeddata lmd_v4 := [7.438,500,5000,1000];
  CONST speeddata lmd_v5 := [7.339,500,5000,1000];
  CONST speeddata lmd_v6 := [7.257,500,5000,1000];
  CONST speeddata lmd_v7 := [7.195,500,5000,1000];
  CONST speeddata lmd_v8 := [7.154,500,5000,1000];
  CONST speeddata lmd_v9 := [7.133,500,5000,1000];
  CONST speeddata lmd_v10 := [7.972,500,5000,1000];
  CONST speeddata lmd_v11 := [8.123,500,5000,1000];
  CONST speeddata lmd_v12 := [8.273,500,5000,1000];
  CONST speeddata lmd_v13 := [8.416,500,5000,1000];
  CONST speeddata lmd_v14 := [8.547,500,5000,1000];
  CONST speeddata lmd_v15 := [8.66,500,5000,1000];
  CONST speeddata lmd_v16 := [8.75,500,5000,1000];
  CONST speeddata lmd_v17 := [8.813,500,5000,1000];
  CONST speeddata lmd_v18 := [8.845,500,5000,1000];
  CONST speeddata lmd_v19 := [250,500,5000,1000];
  CONST speeddata lmd_v20 := [7.821,500,5000,1000];
  CONST speeddata lmd_v21 := [7.68,500,5000,1000];
  CONST speeddata lmd_v22 := [7.55,500,5000,1000];
  CONST speeddata lmd_v23 := [7.434,500,5000,1000];
  CONST speeddata lmd_v24 := [7.356,500,5000,1000];
  CONST speeddata lmd_v25 := [7.311,500,5000,1000];
  CONST speeddata lmd_v26 := [7.253,500,5000,1000];
  CONST speeddata lmd_v27 := [7.192,500,5000,1000];
  CONST speeddata lmd_v28 := [7.152,500,5000,1000];
  CONST speeddata lmd_v29 := [7.132,500,5000,1000];
  CONST speeddata lmd_v30 := [7.153,500,5000,1000];
  CONST speeddata lmd_v31 := [7.194,500,5000,1000];
  CONST speeddata lmd_v32 := [7.256,500,5000,1000];
  CONST speeddata lmd_v33 := [7.313,500,5000,1000];
  CONST speeddata lmd_v34 := [7.359,500,5000,1000];
  CONST speeddata lmd_v35 := [7.685,500,5000,1000];
  CONST speeddata lmd_v36 := [7.826,500,5000,1000];
  CONST speeddata lmd_v37 := [7.974,500,5000,1000];
  CONST speeddata lmd_v38 := [8.126,500,5000,1000];
  CONST speeddata lmd_v39 := [8.277,500,5000,1000];
  CONST speeddata lmd_v40 := [8.422,500,5000,1000];
  CONST speeddata lmd_v41 := [8.524,500,5000,1000];
  CONST speeddata lmd_v42 := [8.586,500,5000,1000];
  CONST speeddata lmd_v43 := [8.666,500,5000,1000];
  CONST speeddata lmd_v44 := [8.755,500,5000,1000];
  CONST speeddata lmd_v45 := [8.816,500,5000,1000];
  CONST speeddata lmd_v46 := [8.846,500,5000,1000];
  CONST speeddata lmd_v47 := [8.814,500,5000,1000];
  CONST speeddata lmd_v48 := [8.753,500,5000,1000];
  CONST speeddata lmd_v49 := [8.663,500,5000,1000];
  CONST speeddata lmd_v50 := [8.582,500,5000,1000];
  CONST zonedata lmd_z := [FALSE,0.2,0.2,0.2,0.02,0.2,0.02];
  VAR triggdata lmd_on;
  VAR triggdata lmd_off;
  VAR triggdata lmd_power;
  VAR triggdata lmd_on_end;
  VAR triggdata lmd_off_end;
  VAR triggdata lmd_power_end;

  PROC main()
    ConfJ \On;
    ConfL \Off;
    SetDO do1, 0;
    SetAO ao1, 0;
    MoveAbsJ lmd_home \NoEOffs, v200, fine, lmd_tool \WObj:=lmd_wobj;
    duct_irbp_irb4600_m001;
    duct_irbp_irb4600_m002;
    WaitRob \InPos;
    SetDO do1, 0;
    SetAO ao1, 0;
    MoveAbsJ lmd_home \NoEOffs, v200, fine, lmd_tool \WObj:=lmd_wobj;
  ENDPROC
ENDMODULE
