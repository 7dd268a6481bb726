MODULE sprocket_tooth_irb
  ! sprocket_tooth_irb: part sprocket_tooth on robot irb, written by lmdc 0.1.0
  ! source tests/cases/rapid/named_signals/input.lmd, sha256 <sha256 of the source>
  ! 3 layers, 45 paths, 90 points; 180 motion instructions (45 with the laser on) in 1 module of at most 2000
  ! plan: 1.78 m deposited, 600.5 mm travel; 5 min 46 s, laser on 4 min 57 s, dwell 7.5 s; 446.1 kJ; powder 39.7 g
  ! units: mm, deg, mm/s; aoLaserPower = 1 is 2000 W
  ! TCP = laser focus, beam along the tool's +Z axis; clearance 5 mm
  PERS tooldata lmd_tool := [TRUE,[[0,0,300],[1,0,0,0]],[18,[0,0,160],[1,0,0,0],0,0,0]];
  PERS wobjdata lmd_wobj := [FALSE,TRUE,"",[[1300,0,400],[1,0,0,0]],[[0,0,0],[1,0,0,0]]];
  CONST jointtarget lmd_home := [[0,0,0,0,90,0],[9E+09,9E+09,9E+09,9E+09,9E+09,9E+09]];
  CONST speeddata lmd_v1 := [6,500,5000,1000];
  CONST speeddata lmd_v2 := [100,500,5000,1000];
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
    SetDO doLaserOn, 0;
    SetAO aoLaserPower, 0;
    MoveAbsJ lmd_home \NoEOffs, v200, fine, lmd_tool \WObj:=lmd_wobj;
    sprocket_tooth_irb_m001;
    WaitRob \InPos;
    SetDO doLaserOn, 0;
    SetAO aoLaserPower, 0;
    MoveAbsJ lmd_home \NoEOffs, v200, fine, lmd_tool \WObj:=lmd_wobj;
  ENDPROC
ENDMODULE
