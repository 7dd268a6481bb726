MODULE small_duct_irb_m001
  ! small_duct_irb module 1: 20 motion instructions, layers 1..2
  ! source tests/cases/rapid/small_duct/input.lmd, sha256 <sha256 of the source>; lmdc 0.1.0
  PROC small_duct_irb_m001()
    ! layer 1 of 5: station 0.0000, height 0.597..0.660 mm, 1 path, 9 points
    MoveJ [[0,3,1.43],[0,1,0,0],[0,0,0,0],[0,0,9E+09,9E+09,9E+09,9E+09]], v200, fine, lmd_tool \WObj:=lmd_wobj;
    MoveL [[0,3,-8.57],[0,1,0,0],[0,0,0,0],[0,0,9E+09,9E+09,9E+09,9E+09]], lmd_v1, fine, lmd_tool \WObj:=lmd_wobj;
    TriggIO lmd_power, 0 \Start \AOp:=ao2, 1.0000;
    TriggIO lmd_on, 0 \Start \DOp:=do3, 1;
    TriggL [[-2.121,2.121,-8.57],[0,1,0,0],[0,0,0,0],[0,0,9E+09,9E+09,9E+09,9E+09]], lmd_v1, lmd_power \T2:=lmd_on, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-3,0,-8.57],[0,1,0,0],[0,0,0,0],[0,0,9E+09,9E+09,9E+09,9E+09]], lmd_v2, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-2.121,-2.121,-8.57],[0,1,0,0],[0,0,0,0],[0,0,9E+09,9E+09,9E+09,9E+09]], lmd_v2, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[0,-3,-8.57],[0,1,0,0],[0,0,0,0],[0,0,9E+09,9E+09,9E+09,9E+09]], lmd_v1, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[2.121,-2.121,-8.57],[0,1,0,0],[0,0,0,0],[0,0,9E+09,9E+09,9E+09,9E+09]], lmd_v3, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[3,0,-8.57],[0,1,0,0],[0,0,0,0],[0,0,9E+09,9E+09,9E+09,9E+09]], lmd_v4, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[2.121,2.121,-8.57],[0,1,0,0],[0,0,0,0],[0,0,9E+09,9E+09,9E+09,9E+09]], lmd_v4, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[0,3,-8.57],[0,1,0,0],[0,0,0,0],[0,0,9E+09,9E+09,9E+09,9E+09]], lmd_v3, fine, lmd_tool \WObj:=lmd_wobj;
    ! layer 2 of 5: station 0.2000, height 0.597..0.659 mm, 1 path, 9 points
    TriggIO lmd_off, 0 \Start \DOp:=do3, 0;
    TriggL [[0,3,1.43],[0,1,0,0],[0,0,0,0],[0,0,9E+09,9E+09,9E+09,9E+09]], lmd_v5, lmd_off, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-0.451,2.963,2.063],[0,0.999986,0,-0.005236],[0,0,0,0],[0.6,0,9E+09,9E+09,9E+09,9E+09]], lmd_v6, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-0.556,2.963,-7.936],[0,0.999986,0,-0.005236],[0,0,0,0],[0.6,0,9E+09,9E+09,9E+09,9E+09]], lmd_v7, fine, lmd_tool \WObj:=lmd_wobj;
    TriggIO lmd_power, 0 \Start \AOp:=ao2, 0.7625;
    TriggIO lmd_on, 0 \Start \DOp:=do3, 1;
    TriggL [[-2.688,1.89,-7.914],[0,0.999986,0,-0.005236],[0,0,0,0],[0.6,0,9E+09,9E+09,9E+09,9E+09]], lmd_v7, lmd_power \T2:=lmd_on, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-3.049,-0.469,-7.91],[0,0.999986,0,-0.005236],[0,0,0,0],[0.6,0,9E+09,9E+09,9E+09,9E+09]], lmd_v8, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-1.976,-2.601,-7.921],[0,0.999986,0,-0.005236],[0,0,0,0],[0.6,0,9E+09,9E+09,9E+09,9E+09]], lmd_v9, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[0.383,-2.963,-7.946],[0,0.999986,0,-0.005236],[0,0,0,0],[0.6,0,9E+09,9E+09,9E+09,9E+09]], lmd_v10, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[2.515,-1.89,-7.968],[0,0.999986,0,-0.005236],[0,0,0,0],[0.6,0,9E+09,9E+09,9E+09,9E+09]], lmd_v11, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[2.876,0.469,-7.972],[0,0.999986,0,-0.005236],[0,0,0,0],[0.6,0,9E+09,9E+09,9E+09,9E+09]], lmd_v12, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[1.803,2.601,-7.961],[0,0.999986,0,-0.005236],[0,0,0,0],[0.6,0,9E+09,9E+09,9E+09,9E+09]], lmd_v13, lmd_z, lmd_tool \WObj:=lmd_wobj;
  ENDPROC
ENDMODULE
