<?xml version="1.0" encoding="UTF-8"?>
<tileset version="1.10" tiledversion="1.10.2" name="terrain" tilewidth="16" tileheight="16" tilecount="8" columns="8">
 <image source="terrain.png" width="128" height="16"/>
 <tile id="1">
  <objectgroup draworder="index" id="2">
   <object id="1" x="0" y="0" width="16" height="16"/>
  </objectgroup>
 </tile>
 <tile id="2">
  <objectgroup draworder="index" id="2">
   <object id="1" x="0" y="16">
    <polygon points="0,0 16,0 16,-16"/>
   </object>
  </objectgroup>
 </tile>
 <tile id="3">
  <properties>
   <property name="collision" value="one_way"/>
  </properties>
 </tile>
 <tile id="4">
  <properties>
   <property name="collision" value="ladder"/>
  </properties>
 </tile>
 <tile id="5">
  <properties>
   <property name="collision" value="empty"/>
  </properties>
 </tile>
</tileset>
