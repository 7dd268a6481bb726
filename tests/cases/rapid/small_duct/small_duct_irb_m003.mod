MODULE small_duct_irb_m003
  ! small_duct_irb module 3: 18 motion instructions, the rest of layer 4, layer 5
  ! source tests/cases/rapid/small_duct/input.lmd, sha256 <sha256 of the source>; lmdc 0.1.0
  PROC small_duct_irb_m003()
    MoveL [[1.122,-2.673,-6.724],[0,0.999877,0,-0.015707],[0,0,0,0],[1.8,0,9E+09,9E+09,9E+09,9E+09]], lmd_v28, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[3.271,-1.141,-6.791],[0,0.999877,0,-0.015707],[0,0,0,0],[1.8,0,9E+09,9E+09,9E+09,9E+09]], lmd_v29, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[2.432,1.362,-6.765],[0,0.999877,0,-0.015707],[0,0,0,0],[1.8,0,9E+09,9E+09,9E+09,9E+09]], lmd_v30, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[0.901,3.513,-6.717],[0,0.999877,0,-0.015707],[0,0,0,0],[1.8,0,9E+09,9E+09,9E+09,9E+09]], lmd_v31, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-1.601,2.673,-6.638],[0,0.999877,0,-0.015707],[0,0,0,0],[1.8,0,9E+09,9E+09,9E+09,9E+09]], lmd_v32, fine, lmd_tool \WObj:=lmd_wobj;
    ! layer 5 of 5: station 0.8000, height 0.587..0.669 mm, 1 path, 9 points
    TriggIO lmd_off, 0 \Start \DOp:=do3, 0;
    TriggL [[-1.287,2.673,3.357],[0,0.999877,0,-0.015707],[0,0,0,0],[1.8,0,9E+09,9E+09,9E+09,9E+09]], lmd_v5, lmd_off, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-1.287,2.673,3.42],[0,0.999877,0,-0.015707],[0,0,0,0],[1.8,0,9E+09,9E+09,9E+09,9E+09]], lmd_v5, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-1.649,2.427,4.015],[0,0.999781,0,-0.020942],[0,0,0,0],[2.4,0,9E+09,9E+09,9E+09,9E+09]], lmd_v33, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-2.068,2.427,-5.976],[0,0.999781,0,-0.020942],[0,0,0,0],[2.4,0,9E+09,9E+09,9E+09,9E+09]], lmd_v34, fine, lmd_tool \WObj:=lmd_wobj;
    TriggIO lmd_on, 0 \Start \DOp:=do3, 1;
    TriggL [[-4.213,0.619,-5.886],[0,0.999781,0,-0.020942],[0,0,0,0],[2.4,0,9E+09,9E+09,9E+09,9E+09]], lmd_v34, lmd_on, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-2.731,-1.763,-5.948],[0,0.999781,0,-0.020942],[0,0,0,0],[2.4,0,9E+09,9E+09,9E+09,9E+09]], lmd_v35, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-0.925,-3.91,-6.024],[0,0.999781,0,-0.020942],[0,0,0,0],[2.4,0,9E+09,9E+09,9E+09,9E+09]], lmd_v36, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[1.456,-2.427,-6.124],[0,0.999781,0,-0.020942],[0,0,0,0],[2.4,0,9E+09,9E+09,9E+09,9E+09]], lmd_v37, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[3.6,-0.619,-6.214],[0,0.999781,0,-0.020942],[0,0,0,0],[2.4,0,9E+09,9E+09,9E+09,9E+09]], lmd_v38, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[2.119,1.763,-6.152],[0,0.999781,0,-0.020942],[0,0,0,0],[2.4,0,9E+09,9E+09,9E+09,9E+09]], lmd_v39, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[0.312,3.91,-6.076],[0,0.999781,0,-0.020942],[0,0,0,0],[2.4,0,9E+09,9E+09,9E+09,9E+09]], lmd_v40, lmd_z, lmd_tool \WObj:=lmd_wobj;
    MoveL [[-2.068,2.427,-5.976],[0,0.999781,0,-0.020942],[0,0,0,0],[2.4,0,9E+09,9E+09,9E+09,9E+09]], lmd_v41, fine, lmd_tool \WObj:=lmd_wobj;
    TriggIO lmd_off, 0 \Start \DOp:=do3, 0;
    TriggL [[-1.649,2.427,4.015],[0,0.999781,0,-0.020942],[0,0,0,0],[2.4,0,9E+09,9E+09,9E+09,9E+09]], lmd_v5, lmd_off, fine, lmd_tool \WObj:=lmd_wobj;
  ENDPROC
ENDMODULE
