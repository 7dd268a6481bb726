MODULE small_duct_irb_m002
  ! small_duct_irb module 2: 20 motion instructions, the rest of layer 2, layers 3..4
  ! source tests/cases/rapid/small_duct/input.lmd, sha256 <sha256 of the source>; lmdc 0.1.0
  PROC small_duct_irb_m002()
    MoveL [[-0.556,2.963,-7.936],[0,0.999986,0,-0.005236],[0,0,0,0],[0.6,0,9E+09,9E+09,9E+09,9E+09]], lmd_v14, fine, lmd_tool \WObj:=lmd_wobj;
    ! layer 3 of 5: station 0.4000, height 0.596..0.660 mm, 1 path, 9 points
    TriggIO lmd_off, 0 \Start \DOp:=do3, 0;
    TriggL [[-0.451,2.963,2.063],[0,0.999986,0,-0.005236],[0,0,0,0],[0.6,0,9E+09,9E+09,9E+09,9E+09]], lmd_v5, lmd_off, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-0.451,2.963,2.088],[0,0.999986,0,-0.005236],[0,0,0,0],[0.6,0,9E+09,9E+09,9E+09,9E+09]], lmd_v5, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-0.884,2.853,2.706],[0,0.999945,0,-0.010472],[0,0,0,0],[1.2,0,9E+09,9E+09,9E+09,9E+09]], lmd_v15, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-1.093,2.853,-7.292],[0,0.999945,0,-0.010472],[0,0,0,0],[1.2,0,9E+09,9E+09,9E+09,9E+09]], lmd_v16, fine, lmd_tool \WObj:=lmd_wobj;
    TriggIO lmd_power, 0 \Start \AOp:=ao2, 0.5250;
    TriggIO lmd_on, 0 \Start \DOp:=do3, 1;
    TriggL [[-3.236,1.564,-7.247],[0,0.999945,0,-0.010472],[0,0,0,0],[1.2,0,9E+09,9E+09,9E+09,9E+09]], lmd_v16, lmd_power \T2:=lmd_on, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-3.019,-0.927,-7.252],[0,0.999945,0,-0.010472],[0,0,0,0],[1.2,0,9E+09,9E+09,9E+09,9E+09]], lmd_v17, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-1.73,-3.07,-7.279],[0,0.999945,0,-0.010472],[0,0,0,0],[1.2,0,9E+09,9E+09,9E+09,9E+09]], lmd_v18, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[0.761,-2.853,-7.331],[0,0.999945,0,-0.010472],[0,0,0,0],[1.2,0,9E+09,9E+09,9E+09,9E+09]], lmd_v19, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[2.904,-1.564,-7.376],[0,0.999945,0,-0.010472],[0,0,0,0],[1.2,0,9E+09,9E+09,9E+09,9E+09]], lmd_v20, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[2.686,0.927,-7.371],[0,0.999945,0,-0.010472],[0,0,0,0],[1.2,0,9E+09,9E+09,9E+09,9E+09]], lmd_v21, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[1.398,3.07,-7.344],[0,0.999945,0,-0.010472],[0,0,0,0],[1.2,0,9E+09,9E+09,9E+09,9E+09]], lmd_v22, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-1.093,2.853,-7.292],[0,0.999945,0,-0.010472],[0,0,0,0],[1.2,0,9E+09,9E+09,9E+09,9E+09]], lmd_v23, fine, lmd_tool \WObj:=lmd_wobj;
    ! layer 4 of 5: station 0.6000, height 0.592..0.665 mm, 1 path, 9 points
    TriggIO lmd_off, 0 \Start \DOp:=do3, 0;
    TriggL [[-0.884,2.853,2.706],[0,0.999945,0,-0.010472],[0,0,0,0],[1.2,0,9E+09,9E+09,9E+09,9E+09]], lmd_v5, lmd_off, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-0.884,2.853,2.748],[0,0.999945,0,-0.010472],[0,0,0,0],[1.2,0,9E+09,9E+09,9E+09,9E+09]], lmd_v5, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-1.287,2.673,3.357],[0,0.999877,0,-0.015707],[0,0,0,0],[1.8,0,9E+09,9E+09,9E+09,9E+09]], lmd_v24, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-1.601,2.673,-6.638],[0,0.999877,0,-0.015707],[0,0,0,0],[1.8,0,9E+09,9E+09,9E+09,9E+09]], lmd_v25, fine, lmd_tool \WObj:=lmd_wobj;
    TriggIO lmd_on, 0 \Start \DOp:=do3, 1;
    TriggL [[-3.751,1.141,-6.571],[0,0.999877,0,-0.015707],[0,0,0,0],[1.8,0,9E+09,9E+09,9E+09,9E+09]], lmd_v25, lmd_on, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-2.911,-1.362,-6.597],[0,0.999877,0,-0.015707],[0,0,0,0],[1.8,0,9E+09,9E+09,9E+09,9E+09]], lmd_v26, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-1.38,-3.513,-6.645],[0,0.999877,0,-0.015707],[0,0,0,0],[1.8,0,9E+09,9E+09,9E+09,9E+09]], lmd_v27, lmd_z, lmd_tool \WObj:=lmd_wobj;
  ENDPROC
ENDMODULE
